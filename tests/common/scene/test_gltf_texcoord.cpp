// Tests of the loader's texture coordinate sets and KHR_materials_specular textures (issue
// #46; common/scene/gltf_textures.cpp, gltf_loader.cpp): which set each texture slot names,
// TEXCOORD_1 read per corner, TEXCOORD_2 and above named once and read through TEXCOORD_0,
// and the specular textures' slots, transforms and factor. What they do in images:
// tests/stages/test_texcoord_images.cpp.
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

namespace test_gltf_texcoord {  // this file's names: the unity build compiles it with others (tests/CMakeLists.txt)

namespace {

const std::vector<glm::vec3> kQuad = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
const std::vector<glm::vec2> kUv0 = {{0.1f, 0.2f}, {0.3f, 0.4f}, {0.5f, 0.6f}, {0.7f, 0.8f}};
const std::vector<glm::vec2> kUv1 = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};

std::string write(GltfWriter& g, const std::string& name) {
  return g.write(pt_test::scratch_dir("pt_gltf_texcoord").string() + "/" + name + ".gltf");
}

}  // namespace

TEST_CASE("texCoord: each texture slot names its set; TEXCOORD_1 is read at every corner; texCoord 2 is named "
          "once and read through TEXCOORD_0",
          "[loader][texture][texcoord]") {
  GltfWriter g;
  int tex = image_texture(g, 1, 1, {rgba(10, 20, 30, 255)});
  GltfWriter::Json m = {{"pbrMetallicRoughness",
                         {{"baseColorTexture", {{"index", tex}, {"texCoord", 1}}},
                          {"metallicRoughnessTexture",
                           {{"index", tex}, {"extensions", {{"KHR_texture_transform", {{"texCoord", 1}}}}}}}}},
                        {"emissiveTexture", {{"index", tex}, {"texCoord", 2}}},
                        {"emissiveFactor", {1, 1, 1}}};
  g.node({{"mesh", textured_quad(g, kQuad, kUv0, kUv1, g.material(m))}});
  pt_test::StderrCapture capture;
  Scene scene = load_gltf(write(g, "sets"));
  std::string err = capture.text();
  INFO("stderr: " << err);
  const MaterialTextures& mt = scene.material_textures.at(0);
  // KHR_texture_transform's texCoord overrides the textureInfo's.
  CHECK(mt.tex_coord_sets == ((1u << kSlotBaseColor) | (1u << kSlotMetallicRoughness)));
  REQUIRE(scene.triangle_attributes.size() == 2);
  const TriangleAttributes &a = scene.triangle_attributes[0], &b = scene.triangle_attributes[1];
  CHECK(a.uv0 == kUv0[0]);
  CHECK(a.uv2 == kUv0[2]);
  CHECK(a.set1_uv0 == kUv1[0]);
  CHECK(a.set1_uv1 == kUv1[1]);
  CHECK(a.set1_uv2 == kUv1[2]);
  CHECK(b.set1_uv1 == kUv1[2]);
  CHECK(b.set1_uv2 == kUv1[3]);
  CHECK(pt_test::occurrences(err, "TEXCOORD_2; only TEXCOORD_0 and TEXCOORD_1 are modelled") == 1);
}

TEST_CASE("texCoord: a file whose textures all read TEXCOORD_0 keeps set 1 at (0, 0) and every slot on set 0",
          "[loader][texture][texcoord]") {
  GltfWriter g;
  int tex = image_texture(g, 1, 1, {rgba(10, 20, 30, 255)});
  GltfWriter::Json m = {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", tex}}}}}};
  g.node({{"mesh", textured_quad(g, kQuad, kUv0, kUv1, g.material(m))}});
  Scene scene = load_gltf(write(g, "set0"));
  CHECK(scene.material_textures.at(0).tex_coord_sets == 0u);
  CHECK(scene.triangle_attributes.at(0).uv1 == kUv0[1]);
  CHECK(scene.triangle_attributes.at(0).set1_uv1 == glm::vec2(0.0f));  // not read: no texture uses it
}

TEST_CASE("KHR_materials_specular: specularTexture and specularColorTexture fill their slots with set, transform "
          "and specularColorFactor; a material without a layer reads neither",
          "[loader][texture][specular_texture]") {
  GltfWriter g;
  int tex = image_texture(g, 1, 1, {rgba(255, 128, 64, 128)});
  int tex2 = image_texture(g, 1, 1, {rgba(1, 2, 3, 4)});
  GltfWriter::Json layered = {
      {"pbrMetallicRoughness", {{"metallicFactor", 0.0}}},
      {"extensions",
       {{"KHR_materials_specular",
         {{"specularFactor", 0.5},
          {"specularTexture", {{"index", tex}, {"texCoord", 1}}},
          {"specularColorFactor", {2.0, 3.0, 4.0}},
          {"specularColorTexture",
           {{"index", tex2}, {"extensions", {{"KHR_texture_transform", {{"offset", {0.25, 0.5}}}}}}}}}}}}};
  GltfWriter::Json no_layer = layered;
  no_layer["extensions"]["KHR_materials_specular"]["specularFactor"] = 0.0;
  g.node({{"mesh", textured_quad(g, kQuad, kUv0, kUv1, g.material(layered))}});
  g.node({{"mesh", textured_quad(g, kQuad, kUv0, kUv1, g.material(no_layer))}});
  g.uses("KHR_materials_specular");
  pt_test::StderrCapture capture;
  Scene scene = load_gltf(write(g, "specular"));
  std::string err = capture.text();
  INFO("stderr: " << err);
  REQUIRE(scene.material_textures.size() == 2);
  const MaterialTextures& mt = scene.material_textures[0];
  CHECK(scene.materials[0].kind == kMaterialDielectric);
  CHECK(mt.specular != kNoTexture);
  CHECK(mt.specular_color != kNoTexture);
  CHECK(mt.specular != mt.specular_color);
  CHECK(mt.tex_coord_sets == 1u << kSlotSpecular);
  CHECK(mt.specular_color_s == glm::vec3(1.0f, 0.0f, 0.25f));
  CHECK(mt.specular_color_t == glm::vec3(0.0f, 1.0f, 0.5f));
  CHECK(mt.specular_color_factor == glm::vec3(2.0f, 3.0f, 4.0f));
  CHECK(scene.materials[0].specular == 0.5f);
  // Without a layer (specularFactor 0: Lambert) the textures vary nothing and are not read.
  CHECK(scene.materials[1].kind == kMaterialDiffuse);
  CHECK(scene.material_textures[1].specular == kNoTexture);
  CHECK(scene.material_textures[1].specular_color == kNoTexture);
  CHECK(err.find("KHR_materials_specular") == std::string::npos);  // modelled, textures too
}

TEST_CASE("KHR_materials_specular: a specular texture without an index or out of range is exit 3, named",
          "[loader][texture][specular_texture]") {
  for (const GltfWriter::Json& info : {GltfWriter::Json{{"texCoord", 0}}, GltfWriter::Json{{"index", 7}}}) {
    GltfWriter g;
    GltfWriter::Json m = {{"pbrMetallicRoughness", {{"metallicFactor", 0.0}}},
                          {"extensions", {{"KHR_materials_specular", {{"specularColorTexture", info}}}}}};
    g.node({{"mesh", textured_quad(g, kQuad, kUv0, {}, g.material(m))}});
    require_bad_scene(write(g, "bad_specular"), {"materials[0].extensions.KHR_materials_specular.specularColorTexture"});
  }
}

}  // namespace test_gltf_texcoord
