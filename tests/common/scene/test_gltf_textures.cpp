// Tests of the glTF loader's textures and vertex colours (issue #19; common/scene/gltf_textures.h):
// what the texture table, the texels, the materials' texture slots and the triangles'
// attributes hold for the fixtures of tests/data/gltf (valid_fixtures.py: textures()), the
// images decoded by OpenImageIO (PNG and JPEG, grey, grey and alpha, 16-bit), the files
// refused with exit 3, and what the host derives from textures: the feature set and the
// light table's powers.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <OpenImageIO/imageio.h>

#include "common/scene/gltf_textures.h"
#include "tests/support/cli_run.h"
#include "tests/support/gltf_checks.h"
#include "tests/support/stderr_capture.h"
#include "tests/support/texels.h"

using namespace pt;
using namespace pt::test;

namespace {

// Collects what is written to stderr (file descriptor 2) while it lives.

using pt_test::rgba;

void check_row(glm::vec3 got, glm::vec3 want) {
  INFO("got (" << got.x << ", " << got.y << ", " << got.z << "), want (" << want.x << ", " << want.y << ", "
               << want.z << ")");
  CHECK(got.x == Approx(want.x).margin(1e-6));
  CHECK(got.y == Approx(want.y).margin(1e-6));
  CHECK(got.z == Approx(want.z).margin(1e-6));
}

}  // namespace

TEST_CASE("textures: the texture table, texels, slots, uv transforms, TEXCOORD_0 and COLOR_0 of a file",
          "[texture][loader]") {
  pt_test::StderrCapture capture;
  Scene scene = load("tex_basic.gltf");
  std::string err = capture.text();
  INFO("stderr: " << err);
  REQUIRE(uses_textures(scene));
  REQUIRE(scene.materials.size() == 1);  // materials[1] is used by no primitive: its images are never read
  REQUIRE(scene.material_textures.size() == 1);
  REQUIRE(scene.triangles.size() == 2);
  REQUIRE(scene.triangle_attributes.size() == 2);
  // Textures 0 and 1 share images[0] (decoded once), with their own samplers.
  REQUIRE(scene.textures.size() == 3);
  const Texture &base = scene.textures[0], &emissive = scene.textures[1], &mr = scene.textures[2];
  CHECK(base.width == 2);
  CHECK(base.height == 2);
  CHECK(base.wrap_s == kWrapClampToEdge);
  CHECK(base.wrap_t == kWrapMirroredRepeat);
  CHECK(base.mag_filter == kFilterNearest);
  CHECK(emissive.offset == base.offset);
  CHECK(emissive.wrap_s == kWrapRepeat);
  CHECK(emissive.wrap_t == kWrapRepeat);
  CHECK(emissive.mag_filter == kFilterLinear);
  CHECK(mr.width == 1);
  CHECK(mr.height == 1);
  REQUIRE(scene.texels.size() == 5);
  // Rows from the image's top, RGBA with R in the low byte; alpha kept straight.
  CHECK(scene.texels[base.offset + 0] == rgba(255, 0, 0, 255));
  CHECK(scene.texels[base.offset + 1] == rgba(0, 255, 0, 255));
  CHECK(scene.texels[base.offset + 2] == rgba(0, 0, 255, 255));
  CHECK(scene.texels[base.offset + 3] == rgba(128, 128, 128, 128));
  CHECK(base.texel_min == rgba(0, 0, 0, 128));
  CHECK(base.texel_max == rgba(255, 255, 255, 255));
  // A 16-bit RGB image rounded to 8 bits: 0, 32896 and 65535 of 65535 are 0, 128 and 255.
  CHECK(scene.texels[mr.offset] == rgba(0, 128, 255, 255));
  // The material's slots, factors and transforms.
  const MaterialTextures& mt = scene.material_textures[0];
  CHECK(mt.base_color == 0u);
  CHECK(mt.emissive == 1u);
  CHECK(mt.metallic_roughness == 2u);
  CHECK(mt.metallic_factor == 0.75f);
  CHECK(mt.roughness_factor == 0.5f);
  check_row(mt.base_color_s, {1, 0, 0});
  check_row(mt.base_color_t, {0, 1, 0});
  // offset (0.25, 0.5), rotation 0.3, scale (2, 3): rows (c sx, s sy, ox) and (-s sx, c sy, oy).
  const float c = std::cos(0.3f), s = std::sin(0.3f);
  check_row(mt.emissive_s, {2 * c, 3 * s, 0.25f});
  check_row(mt.emissive_t, {-2 * s, 3 * c, 0.5f});
  // The quad's two triangles (0 1 2, 0 2 3) with the corners' TEXCOORD_0 and COLOR_0.
  const TriangleAttributes &t0 = scene.triangle_attributes[0], &t1 = scene.triangle_attributes[1];
  CHECK(t0.uv0 == glm::vec2(0, 0));
  CHECK(t0.uv1 == glm::vec2(1, 0));
  CHECK(t0.uv2 == glm::vec2(1, 1));
  CHECK(t1.uv2 == glm::vec2(0, 1));
  CHECK(t0.color0 == glm::vec4(1, 0, 0, 1));
  CHECK(t0.color1 == glm::vec4(0, 1, 0, 1));
  CHECK(t0.color2 == glm::vec4(0, 0, 1, 0.5f));
  CHECK(t1.color2 == glm::vec4(1, 1, 1, 1));
  // The factors stay in the material.
  check_point(scene.materials[0].base_color, {0.5f, 0.25f, 1.0f});
  // Named once each: what stays unmodelled. Textures themselves are no longer warned about.
  CHECK(pt_test::occurrences(err, "normal textures") == 1);
  CHECK(pt_test::occurrences(err, "occlusion textures") == 1);
  CHECK(pt_test::occurrences(err, "not modelled (base colour") == 0);
  CHECK(err.find("KHR_texture_transform") == std::string::npos);  // a supported extension
}

TEST_CASE("textures: the feature set has textures, and every kind a metallic-roughness texture reaches",
          "[texture][features]") {
  Scene scene = load("tex_basic.gltf");
  // metallic 0.75 x B (255): mixed; roughness 0.5 x G (128): GGX. The diffuse lobe is mixed's.
  uint mask = scene_feature_mask(scene, glm::vec3(0.0f));
  CHECK((mask & kFeatureTextures) != 0u);
  CHECK((mask & kFeatureMixed) != 0u);
  CHECK((mask & kFeatureDiffuse) != 0u);
  CHECK((mask & kFeatureConductor) != 0u);
  CHECK((mask & kFeatureMirror) == 0u);
  CHECK(feature_names(mask).find("textures") != std::string::npos);
  // Texels whose blue runs from 0 to 255 and green from 0: with metallic and roughness
  // factors 1, every kind: diffuse (B 0), mixed, mirror (G 0) and GGX.
  scene.textures[2].texel_min = rgba(0, 0, 0, 255);
  scene.textures[2].texel_max = rgba(0, 255, 255, 255);
  scene.material_textures[0].metallic_factor = 1.0f;
  scene.material_textures[0].roughness_factor = 1.0f;
  mask = scene_feature_mask(scene, glm::vec3(0.0f));
  const uint lobes = kFeatureDiffuse | kFeatureMirror | kFeatureConductor | kFeatureMixed;
  CHECK((mask & lobes) == lobes);
  // Without textures: no texture code, and the factors' kinds alone.
  Scene plain = load("materials.gltf");
  CHECK((scene_feature_mask(plain, glm::vec3(0.0f)) & kFeatureTextures) == 0u);
  CHECK_FALSE(uses_textures(plain));
}

TEST_CASE("textures: grey, grey and alpha, and RGB images become RGBA texels", "[texture][loader]") {
  Scene scene = load("tex_channels.gltf");
  REQUIRE(scene.textures.size() == 3);
  const MaterialTextures& mt = scene.material_textures.at(0);
  const Texture &grey = scene.textures[mt.base_color], &grey_alpha = scene.textures[mt.emissive],
                &rgb = scene.textures[mt.metallic_roughness];
  CHECK(scene.texels[grey.offset] == rgba(0, 0, 0, 255));
  CHECK(scene.texels[grey.offset + 1] == rgba(200, 200, 200, 255));
  CHECK(scene.texels[grey_alpha.offset] == rgba(77, 77, 77, 99));
  CHECK(scene.texels[rgb.offset] == rgba(10, 20, 30, 255));
  CHECK(texel_value(scene, grey, 1, 0) == glm::vec4(200.0f / 255.0f, 200.0f / 255.0f, 200.0f / 255.0f, 1.0f));
}

TEST_CASE("textures: an image file next to the scene is read; texCoord 1 is named once and read as TEXCOORD_0",
          "[texture][loader]") {
  pt_test::StderrCapture capture;
  Scene scene = load("tex_external.gltf");
  std::string err = capture.text();
  INFO("stderr: " << err);
  REQUIRE(scene.textures.size() == 1);
  CHECK(scene.texels.at(scene.textures[0].offset) == rgba(10, 20, 30, 40));
  CHECK(pt_test::occurrences(err, "TEXCOORD_1") == 1);
}

TEST_CASE("textures: KHR_texture_transform's example maps uv onto the image's lower-left quadrant, turned",
          "[texture][loader]") {
  // offset (0, 1), rotation pi/2, scale 0.5: (u, v) -> (v / 2, 1 - u / 2).
  Scene scene = load("tex_transform.gltf");
  const MaterialTextures& mt = scene.material_textures.at(0);
  auto apply = [&](glm::vec2 uv) {
    return glm::vec2(glm::dot(mt.base_color_s, glm::vec3(uv, 1.0f)), glm::dot(mt.base_color_t, glm::vec3(uv, 1.0f)));
  };
  for (glm::vec2 uv : {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(0, 1), glm::vec2(1, 1), glm::vec2(0.3f, 0.8f)}) {
    glm::vec2 got = apply(uv), want(0.5f * uv.y, 1.0f - 0.5f * uv.x);
    INFO("uv (" << uv.x << ", " << uv.y << ") -> (" << got.x << ", " << got.y << ")");
    CHECK(got.x == Approx(want.x).margin(1e-6));
    CHECK(got.y == Approx(want.y).margin(1e-6));
  }
}

TEST_CASE("textures: an image outside the scene's folder is refused with exit 3", "[texture][loader]") {
  require_bad_scene(fixture("tex_outside.gltf"), {"images[0].uri", "outside the scene's folder"});
  require_bad_scene(fixture("tex_outside_encoded.gltf"), {"images[0].uri", "outside the scene's folder"});
}

TEST_CASE("textures: a used image that is missing, damaged, not PNG or JPEG, or too large is exit 3 naming it",
          "[stage1][texture][loader]") {
  require_bad_scene(fixture("tex_missing.gltf"), {"images[0]", "tex_missing.png", "not found"});
  require_bad_scene(fixture("tex_malformed.gltf"), {"images[0]", "baseColorTexture", "truncated PNG"});
  require_bad_scene(fixture("tex_not_png.gltf"), {"images[0]", "neither a PNG nor a JPEG"});
  require_bad_scene(fixture("tex_truncated.glb"), {"images[0]", "truncated PNG", "re-export"});
  // Its chunks intact, its compressed data not: OpenImageIO's decoder says so. libpng's
  // own line on stderr is kept out: the program says one line (the contract's errors).
  require_bad_scene(fixture("tex_bad_deflate.glb"), {"images[0]", "cannot be decoded"});
  const std::filesystem::path run_dir = pt_test::scratch_dir("pt_textures_run");
  pt_test::Run r = pt_test::run_program(
      PT_STAGE1_BIN, "--backend cpu --out " + (run_dir / "bad.exr").string() + " --scene " + fixture("tex_bad_deflate.glb"),
      "", run_dir);
  pt_test::check_error(r, "stage1_raycast", pt::kExitBadScene, "cannot be decoded");
  require_bad_scene(fixture("tex_oversized.gltf"), {"images[0]", "16385 x 1", "16384 x 16384", "downscale"});
  // Two images of 16384 x 16384: 2 GiB of texels, refused before either is decoded.
  require_bad_scene(fixture("tex_total.glb"), {"2048 MiB", "1024 MiB limit", "images[0]", "downscale"});
}

TEST_CASE("textures: a sampler's unknown wrap mode or a texture index out of range is exit 3", "[texture][loader]") {
  require_bad_scene(fixture("tex_bad_sampler.gltf"), {"samplers[0].wrapS", "1234", "wrap mode"});
  require_bad_scene(fixture("tex_bad_index.gltf"), {"materials[0].emissiveTexture.index", "out of range"});
}

TEST_CASE("textures: a JPEG image is decoded by OpenImageIO", "[texture][loader]") {
  namespace fs = std::filesystem;
  fs::path dir = fs::temp_directory_path() / ("pt_jpeg_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  {
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create("jpg");
    REQUIRE(out);
    OIIO::ImageSpec spec(8, 8, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("Compression", "jpeg:100");
    REQUIRE(out->open((dir / "flat.jpg").string(), spec));
    std::vector<unsigned char> pixels(8 * 8 * 3);
    for (std::size_t i = 0; i < pixels.size(); i += 3) pixels[i] = 200, pixels[i + 1] = 100, pixels[i + 2] = 50;
    REQUIRE(out->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
    out->close();
  }
  // tex_external.gltf again, with the JPEG as its image.
  std::string text;
  {
    std::ifstream in(fixture("tex_external.gltf"));
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  text.replace(text.find("tex_external.png"), std::string("tex_external.png").size(), "flat.jpg");
  std::ofstream(dir / "jpeg.gltf") << text;
  Scene scene = load_gltf((dir / "jpeg.gltf").string());
  REQUIRE(scene.textures.size() == 1);
  REQUIRE(scene.textures[0].width == 8);
  for (uint i = 0; i < 64; i++) {
    glm::vec4 t = texel_value(scene, scene.textures[0], i % 8, i / 8) * 255.0f;
    CHECK(std::abs(t.x - 200.0f) <= 2.0f);
    CHECK(std::abs(t.y - 100.0f) <= 2.0f);
    CHECK(std::abs(t.z - 50.0f) <= 2.0f);
    CHECK(t.w == 255.0f);
  }
  fs::remove_all(dir);
}

TEST_CASE("textures: the fuzz corpus's image-bearing seed loads", "[texture][loader]") {
  Scene scene = load("tex_seed.glb");
  CHECK(uses_textures(scene));
  CHECK(scene.textures.size() == 2);  // the emissive slot reads the base colour's texture
  CHECK(scene.camera.has_value());
}

TEST_CASE("textures: the light table weighs a textured emitter by its emissive texture's mean", "[texture][lights]") {
  // Two equal triangles of emission 1: one plain, one whose emissive texture's texels are
  // sRGB 255 and 0 (mean 0.5): it gets a third of the picks.
  Scene s;
  uint plain = s.add_material(make_diffuse(glm::vec3(0.0f), glm::vec3(1.0f)));
  uint textured = s.add_material(make_diffuse(glm::vec3(0.0f), glm::vec3(1.0f)));
  s.add_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, plain);
  s.add_triangle({0, 0, 1}, {1, 0, 1}, {0, 1, 1}, textured);
  s.material_textures.assign(2, no_material_textures());
  s.triangle_attributes.assign(2, no_triangle_attributes());
  s.textures.push_back(Texture{0u, 2u, 1u, kWrapRepeat, kWrapRepeat, kFilterLinear, rgba(0, 0, 0, 255),
                               rgba(255, 255, 255, 255)});
  s.texels = {rgba(255, 255, 255, 255), rgba(0, 0, 0, 255)};
  s.material_textures[textured].emissive = 0u;
  build_light_table(s);
  REQUIRE(s.lights.size() == 2);
  CHECK(s.lights[0].pick == Approx(2.0 / 3.0).epsilon(1e-6));
  CHECK(s.lights[1].pick == Approx(1.0 / 3.0).epsilon(1e-6));
  // The pieces stay parallel as a scene grows.
  s.add_material(make_diffuse(glm::vec3(0.5f)));
  s.add_triangle({0, 0, 2}, {1, 0, 2}, {0, 1, 2}, 2u);
  CHECK(s.material_textures.size() == s.materials.size());
  CHECK(s.triangle_attributes.size() == s.triangles.size());
}

TEST_CASE("textures: decode_image reads a PNG from memory and names a damaged one", "[texture][loader]") {
  std::ifstream in(fixture("tex_external.png"), std::ios::binary);
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), {});
  gltf::DecodedImage image = gltf::decode_image(bytes, "test.gltf", "images[0]");
  CHECK(image.width == 1);
  CHECK(image.height == 1);
  CHECK(image.texels.at(0) == rgba(10, 20, 30, 40));
  bytes.resize(bytes.size() - 16);
  int code = 0;
  std::string message;
  try {
    gltf::decode_image(bytes, "test.gltf", "images[7]");
  } catch (const Error& e) {
    code = e.code(), message = e.what();
  }
  CHECK(code == kExitBadScene);
  CHECK_THAT(message, Catch::Contains("images[7]"));
}

TEST_CASE("alphaMode MASK keeps its cutoff and the base colour's alpha; BLEND is drawn opaque and said once",
          "[texture][loader][alpha_mask]") {
  pt_test::StderrCapture capture;
  Scene scene = load("tex_mask.gltf");
  std::string err = capture.text();
  INFO("stderr: " << err);
  REQUIRE(scene.material_textures.size() == 3);
  CHECK(scene.material_textures[0].alpha_cutoff == 0.5f);  // glTF's default cutoff
  CHECK(scene.material_textures[0].base_alpha == 1.0f);
  CHECK(scene.material_textures[1].alpha_cutoff == 0.25f);
  CHECK(scene.material_textures[1].base_alpha == 0.2f);
  CHECK(scene.material_textures[2].alpha_cutoff == 0.0f);  // BLEND: opaque
  CHECK(pt_test::occurrences(err, "alphaMode BLEND") == 1);
  CHECK(pt_test::occurrences(err, "alphaMode MASK") == 0);
  CHECK((scene_feature_mask(scene, glm::vec3(0.0f)) & kFeatureAlphaMask) != 0u);
  CHECK((scene_feature_mask(load("tex_sky_plane.gltf"), glm::vec3(0.0f)) & kFeatureAlphaMask) == 0u);
}
