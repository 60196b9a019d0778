// Tests of the glTF loader's textures and vertex colours (issue #19; common/scene/gltf_textures.h):
// what the texture table, the texels, the materials' texture slots and the triangles'
// attributes hold for the fixtures of tests/data/gltf (texture_fixtures.py: textures()), and
// alphaMode's cutoff. The images themselves, decoded or refused: test_gltf_images.cpp; what
// the host derives from textures: test_texture_scene.cpp.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "common/scene/gltf_textures.h"
#include "tests/support/cli_run.h"
#include "tests/support/gltf_checks.h"
#include "tests/support/stderr_capture.h"
#include "tests/support/texels.h"

using namespace pt;
using namespace pt::test;

namespace {

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
  CHECK(pt_test::occurrences(err, "normal textures") == 0);  // modelled (docs/shading_normals.md)
  CHECK(pt_test::occurrences(err, "occlusion textures") == 1);
  CHECK(pt_test::occurrences(err, "not modelled (base colour") == 0);
  CHECK(err.find("KHR_texture_transform") == std::string::npos);  // a supported extension
}

TEST_CASE("textures: an image file next to the scene is read; texCoord 1 without TEXCOORD_1 is named once and "
          "read at uv (0, 0)",
          "[texture][loader][texcoord]") {
  pt_test::StderrCapture capture;
  Scene scene = load("tex_external.gltf");
  std::string err = capture.text();
  INFO("stderr: " << err);
  REQUIRE(scene.textures.size() == 1);
  CHECK(scene.texels.at(scene.textures[0].offset) == rgba(10, 20, 30, 40));
  CHECK(scene.material_textures.at(0).tex_coord_sets == 1u << kSlotBaseColor);
  CHECK(scene.triangle_attributes.at(0).set1_uv1 == glm::vec2(0.0f));
  CHECK(pt_test::occurrences(err, "has a texture on TEXCOORD_1 but no TEXCOORD_1; its textures there are read at uv (0, 0)") == 1);
  CHECK(pt_test::occurrences(err, "TEXCOORD_0") == 0);  // no texture reads it
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

TEST_CASE("textures: the fuzz corpus's image-bearing seed loads", "[texture][loader]") {
  Scene scene = load("tex_seed.glb");
  CHECK(uses_textures(scene));
  CHECK(scene.textures.size() == 2);  // the emissive slot reads the base colour's texture
  CHECK(scene.camera.has_value());
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
