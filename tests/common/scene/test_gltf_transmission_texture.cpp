// Tests of the loader's KHR_materials_transmission transmissionTexture (issue #46;
// common/scene/gltf_textures.cpp, gltf_materials.cpp): its slot, set and transform, read
// silently; a factor of 1 with a texture stays the glTF dielectric (the texture makes it
// partial); a material without transmission or a pure metal leaves it unread. What it does
// in images: tests/stages/test_transmission_images.cpp.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "common/scene/scene_loading.h"
#include "tests/support/cli_run.h"
#include "tests/support/gltf_checks.h"
#include "tests/support/gltf_textured.h"
#include "tests/support/stderr_capture.h"
#include "tests/support/texels.h"

using namespace pt;
using namespace pt::test;
using pt_test::rgba;

namespace test_gltf_transmission_texture {  // this file's names: the unity build compiles it with others (tests/CMakeLists.txt)

namespace {

const std::vector<glm::vec3> kQuad = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
const std::vector<glm::vec2> kUv0 = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
const std::vector<glm::vec2> kUv1 = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};

std::string write(GltfWriter& g, const std::string& name) {
  return g.write(pt_test::scratch_dir("pt_gltf_transmission_texture").string() + "/" + name + ".gltf");
}

GltfWriter::Json transmissive(double factor, GltfWriter::Json texture, double metallic = 0.0) {
  GltfWriter::Json transmission = {{"transmissionFactor", factor}};
  if (!texture.is_null()) transmission["transmissionTexture"] = texture;
  return {{"pbrMetallicRoughness", {{"metallicFactor", metallic}, {"roughnessFactor", 0.5}}},
          {"extensions", {{"KHR_materials_transmission", transmission}}}};
}

}  // namespace

TEST_CASE("transmissionTexture fills its slot with its set and transform and is read without a warning; "
          "a factor of 1 with a texture stays the glTF dielectric",
          "[loader][texture][transmission_texture]") {
  GltfWriter g;
  int tex = image_texture(g, 1, 1, {rgba(128, 0, 255, 255)});
  GltfWriter::Json info = {{"index", tex},
                           {"texCoord", 1},
                           {"extensions", {{"KHR_texture_transform", {{"offset", {0.25, 0.5}}}}}}};
  g.node({{"mesh", textured_quad(g, kQuad, kUv0, kUv1, g.material(transmissive(1.0, info)))}});
  g.node({{"mesh", textured_quad(g, kQuad, kUv0, kUv1, g.material(transmissive(0.4, {{"index", tex}})))}});
  g.uses("KHR_materials_transmission");
  pt_test::StderrCapture capture;
  Scene scene = load_gltf(write(g, "slots"));
  std::string err = capture.text();
  INFO("stderr: " << err);
  REQUIRE(scene.material_textures.size() == 2);
  const MaterialTextures& mt = scene.material_textures[0];
  // Transmission 1 alone is glass; with a texture some points transmit less, so it is the
  // dielectric whose transmission the texture scales.
  CHECK(scene.materials[0].kind == kMaterialDielectric);
  CHECK(scene.materials[0].transmission == 1.0f);
  CHECK(mt.transmission != kNoTexture);
  CHECK(mt.tex_coord_sets == 1u << kSlotTransmission);
  CHECK(mt.transmission_s == glm::vec3(1.0f, 0.0f, 0.25f));
  CHECK(mt.transmission_t == glm::vec3(0.0f, 1.0f, 0.5f));
  CHECK(scene.materials[1].kind == kMaterialDielectric);
  CHECK(scene.materials[1].transmission == 0.4f);
  CHECK(scene.material_textures[1].transmission == mt.transmission);  // the same texture, one table entry
  CHECK(scene.material_textures[1].tex_coord_sets == 0u);
  CHECK(err.find("transmissionTexture") == std::string::npos);  // modelled
}

TEST_CASE("transmissionTexture is not read where nothing transmits: factor 0, or a pure metal",
          "[loader][texture][transmission_texture]") {
  GltfWriter g;
  int tex = image_texture(g, 1, 1, {rgba(255, 255, 255, 255)});
  g.node({{"mesh", textured_quad(g, kQuad, kUv0, {}, g.material(transmissive(0.0, {{"index", tex}})))}});
  g.node({{"mesh", textured_quad(g, kQuad, kUv0, {}, g.material(transmissive(1.0, {{"index", tex}}, 1.0)))}});
  g.uses("KHR_materials_transmission");
  Scene scene = load_gltf(write(g, "unread"));
  REQUIRE(scene.materials.size() == 2);
  CHECK(scene.materials[0].transmission == 0.0f);
  CHECK(scene.materials[1].kind == kMaterialRoughGlass);  // make_gltf_material: transmission 1 wins over metallic
  // No material reads the texture, so the scene has no texture table at all.
  CHECK(scene.material_textures.empty());
  CHECK(scene.textures.empty());
}

TEST_CASE("a transmissionTexture without an index or out of range is exit 3, named",
          "[loader][texture][transmission_texture]") {
  for (const GltfWriter::Json& info : {GltfWriter::Json{{"texCoord", 0}}, GltfWriter::Json{{"index", 7}}}) {
    GltfWriter g;
    g.node({{"mesh", textured_quad(g, kQuad, kUv0, {}, g.material(transmissive(0.5, info)))}});
    require_bad_scene(write(g, "bad_transmission"),
                      {"materials[0].extensions.KHR_materials_transmission.transmissionTexture"});
  }
}

}  // namespace test_gltf_transmission_texture
