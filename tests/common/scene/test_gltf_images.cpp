// Tests of the glTF loader's texture images (issue #19; common/scene/gltf_textures.h): the
// images decoded by OpenImageIO (PNG and JPEG, grey, grey and alpha, RGB) into RGBA texels,
// and the files refused with exit 3 (an image missing, damaged, too large or outside the
// scene's folder, a sampler's unknown wrap mode, a texture index out of range). What the
// texture table and slots hold: test_gltf_textures.cpp.
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
#include "tests/support/texels.h"

using namespace pt;
using namespace pt::test;
using pt_test::rgba;

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
