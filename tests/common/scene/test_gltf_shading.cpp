// glTF's NORMAL, TANGENT and normalTexture as the loader reads them (issue #46;
// common/scene/gltf_shading.cpp): normals placed by the inverse transpose of the node's
// transform, smooth triangles flagged (and only those), tangents made from the UVs equal to
// the file's, a degenerate UV triangle's tangent, and the normal texture's slot and scale.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include "common/scene/gltf_scene_builder.h"
#include "common/scene/scene_loading.h"
#include "tests/support/gltf_writer.h"

using namespace pt;
using pt::test::GltfWriter;

namespace test_gltf_shading {  // this file's names: the unity build compiles it with others (tests/CMakeLists.txt)

namespace {

namespace fs = std::filesystem;

fs::path scratch() {
  fs::path dir = fs::temp_directory_path() / ("pt_shading_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

// A 2 x 2 normal map (linear RGB) beside the files: flat normals, (128, 128, 255).
std::string write_normal_png(const fs::path& dir) {
  std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create("png");
  REQUIRE(out);
  OIIO::ImageSpec spec(2, 2, 3, OIIO::TypeDesc::UINT8);
  REQUIRE(out->open((dir / "normals.png").string(), spec));
  std::vector<unsigned char> pixels = {128, 128, 255, 128, 128, 255, 128, 128, 255, 128, 128, 255};
  REQUIRE(out->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
  out->close();
  return "normals.png";
}

std::vector<float> flat(const std::vector<glm::vec3>& v) {
  std::vector<float> f;
  for (glm::vec3 x : v) f.insert(f.end(), {x.x, x.y, x.z});
  return f;
}

void require_near(glm::vec3 a, glm::vec3 b, float tolerance = 1e-5f) {
  INFO("(" << a.x << ", " << a.y << ", " << a.z << ") vs (" << b.x << ", " << b.y << ", " << b.z << ")");
  REQUIRE(glm::length(a - b) < tolerance);
}

// A unit quad in the xy plane facing +z, two triangles, uv (x, 1 - y) or mirrored in u;
// `tangents`: the file's TANGENT for that layout. Normal-mapped, placed by `node`.
std::string quad_file(const fs::path& dir, const std::string& name, bool mirrored, bool tangents,
                      GltfWriter::Json node) {
  GltfWriter w;
  int material = w.material({{"pbrMetallicRoughness", {{"metallicFactor", 0.0}}},
                             {"normalTexture", {{"index", w.texture(write_normal_png(dir))}, {"scale", 0.5}}}});
  std::vector<glm::vec3> p = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  std::vector<GltfWriter::Attribute> attributes;
  std::vector<float> uv, normals = flat(std::vector<glm::vec3>(6, glm::vec3(0, 0, 1))), t;
  for (glm::vec3 q : p) uv.insert(uv.end(), {mirrored ? 1.0f - q.x : q.x, 1.0f - q.y});
  for (int i = 0; i < 6; i++) t.insert(t.end(), {mirrored ? -1.0f : 1.0f, 0.0f, 0.0f, mirrored ? -1.0f : 1.0f});
  attributes.push_back({"NORMAL", 3, normals});
  attributes.push_back({"TEXCOORD_0", 2, uv});
  if (tangents) attributes.push_back({"TANGENT", 4, t});
  node["mesh"] = w.mesh_with(p, attributes, material);
  w.node(node);
  return w.write((dir / name).string());
}

}  // namespace

TEST_CASE("shading normals: NORMAL is placed by the inverse transpose and flags only smooth triangles",
          "[shading_normals][loader]") {
  fs::path dir = scratch();
  GltfWriter w;
  // Triangle 0: tilted vertex normals; triangle 1: every normal its face normal.
  std::vector<glm::vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {3, 0, 0}, {2, 1, 0}};
  std::vector<glm::vec3> n = {glm::normalize(glm::vec3(0.3f, 0, 1)), glm::normalize(glm::vec3(0, 0.3f, 1)), {0, 0, 1},
                              {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  w.node({{"mesh", w.mesh_with(p, {{"NORMAL", 3, flat(n)}}, w.diffuse(glm::vec3(0.8f)))}, {"scale", {2.0, 1.0, 1.0}}});
  Scene scene = load_gltf(w.write((dir / "normals.gltf").string()));
  REQUIRE(scene.triangles.size() == 2);
  REQUIRE(scene.triangle_shading.size() == 2);
  CHECK((scene.triangles[0].flags & kTriangleShadingNormals) != 0u);
  CHECK((scene.triangles[1].flags & kTriangleShadingNormals) == 0u);
  CHECK((scene_feature_mask(scene, glm::vec3(0.0f)) & kFeatureShadingNormals) != 0u);
  // Scale (2, 1, 1): normals by diag(1/2, 1, 1), then made unit.
  require_near(scene.triangle_shading[0].normal0, glm::normalize(glm::vec3(0.15f, 0, 1)));
  require_near(scene.triangle_shading[0].normal1, glm::normalize(glm::vec3(0, 0.3f, 1)));
  require_near(scene.triangle_shading[0].normal2, glm::vec3(0, 0, 1));
}

TEST_CASE("shading normals: a file whose normals are its face normals runs no shading-normal code",
          "[shading_normals][loader]") {
  fs::path dir = scratch();
  GltfWriter w;
  std::vector<glm::vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  w.node({{"mesh", w.mesh_with(p, {{"NORMAL", 3, flat({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}})}}, w.diffuse(glm::vec3(0.8f)))}});
  Scene scene = load_gltf(w.write((dir / "flat_normals.gltf").string()));
  CHECK(scene.triangle_shading.empty());
  CHECK((scene_feature_mask(scene, glm::vec3(0.0f)) & kFeatureShadingNormals) == 0u);
}

TEST_CASE("shading normals: tangents made from the UVs equal the file's TANGENT", "[shading_normals][loader]") {
  fs::path dir = scratch();
  const double half = std::sqrt(0.5);
  GltfWriter::Json turned = {{"rotation", {half, 0.0, 0.0, half}}, {"translation", {0.5, -1.0, 2.0}}};
  for (bool mirrored : {false, true}) {
    INFO((mirrored ? "uv mirrored in u" : "uv upright"));
    Scene given = load_gltf(quad_file(dir, "given.gltf", mirrored, true, turned));
    Scene made = load_gltf(quad_file(dir, "made.gltf", mirrored, false, turned));
    REQUIRE(given.triangle_shading.size() == 2);
    REQUIRE(made.triangle_shading.size() == 2);
    CHECK((scene_feature_mask(made, glm::vec3(0.0f)) & kFeatureShadingNormals) != 0u);
    for (std::size_t i = 0; i < 2; i++) {
      const TriangleShading &g = given.triangle_shading[i], &m = made.triangle_shading[i];
      CHECK((given.triangles[i].flags & kTriangleShadingNormals) != 0u);  // normal-mapped
      // The quad turned a quarter about x: +x stays, the handedness with it.
      require_near(g.tangent0, glm::vec3(mirrored ? -1.0f : 1.0f, 0, 0));
      for (glm::vec3 t : {m.tangent0, m.tangent1, m.tangent2}) require_near(t, g.tangent0);
      for (float h : {g.handedness0, m.handedness0, m.handedness1, m.handedness2}) CHECK(h == (mirrored ? -1.0f : 1.0f));
    }
    // The normal texture's slot: its texture, scale and (identity) transform.
    const MaterialTextures& mt = given.material_textures.at(given.triangles[0].material);
    CHECK(mt.normal != kNoTexture);
    CHECK(mt.normal_scale == 0.5f);
    CHECK(mt.normal_s == glm::vec3(1, 0, 0));
    CHECK(mt.normal_t == glm::vec3(0, 1, 0));
  }
}

TEST_CASE("shading normals: a triangle without UV area gets a tangent orthogonal to its normal", "[shading_normals]") {
  const glm::vec3 p[3] = {{0, 0, 0}, {1, 0.2f, 0.1f}, {0.3f, 1, -0.4f}};
  const glm::vec2 uv[3] = {{0.5f, 0.5f}, {0.5f, 0.5f}, {0.5f, 0.5f}};
  const glm::vec3 n = glm::normalize(glm::cross(p[1] - p[0], p[2] - p[0]));
  TriangleShading s = gltf::tangents_from_uvs(p, uv, n);
  for (glm::vec3 t : {s.tangent0, s.tangent1, s.tangent2}) {
    CHECK(std::abs(glm::length(t) - 1.0f) < 1e-5f);
    CHECK(std::abs(glm::dot(t, n)) < 1e-5f);
  }
  CHECK(std::isfinite(s.handedness0));
}

}  // namespace test_gltf_shading
