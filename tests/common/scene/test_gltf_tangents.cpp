// The tangents the loader makes for a normal map where a file has no TANGENT (issue #46;
// common/scene/gltf_tangents.cpp) against Blender's MikkTSpace tangents of the same meshes:
// tests/data/gltf/mikktspace_tangents.gltf, made by make_mikktspace_fixture.py beside it.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include "common/scene/gltf_scene_builder.h"
#include "common/scene/scene_loading.h"
#include "tests/support/gltf_checks.h"

using namespace pt;

namespace {

namespace fs = std::filesystem;

// The fixture with every TANGENT attribute taken out, in a scratch folder (its buffer is a data URI).
std::string without_tangents() {
  std::ifstream in(pt::test::fixture("mikktspace_tangents.gltf"));
  nlohmann::json doc = nlohmann::json::parse(in);
  for (auto& mesh : doc["meshes"]) {
    for (auto& prim : mesh["primitives"]) prim["attributes"].erase("TANGENT");
  }
  fs::path dir = fs::temp_directory_path() / ("pt_tangents_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path out = dir / "no_tangents.gltf";
  std::ofstream(out) << doc.dump();
  return out.string();
}

}  // namespace

// The bounds, measured: on the sphere every vertex's tangent is Blender's to 1e-5 rad (both
// sum the same angle-weighted dP/du; what is left is float rounding), so 1e-4 rad. On the strip
// Blender ran MikkTSpace on its quads, which are twisted here, and the file holds the exporter's
// triangles of them: a non-planar quad's dP/du depends on how it is split, 0.0031 rad at worst
// here, so 5e-3 rad. The per-triangle tangents from the UVs that the loader made before are off
// by up to 0.31 rad on the sphere, 0.055 rad on the strip.
TEST_CASE("normal maps: tangents made where the file has none match Blender's MikkTSpace at every vertex",
          "[shading_normals][loader][gltf]") {
  Scene given = load_gltf(pt::test::fixture("mikktspace_tangents.gltf"));
  Scene made = load_gltf(without_tangents());
  REQUIRE(given.triangles.size() == 88);
  REQUIRE(made.triangles.size() == given.triangles.size());
  REQUIRE(made.triangle_shading.size() == given.triangles.size());
  double worst[2] = {0.0, 0.0};  // the sphere, the strip
  int corners[2] = {0, 0};
  for (std::size_t i = 0; i < given.triangles.size(); ++i) {
    const Triangle& tri = given.triangles[i];
    const int strip = (tri.p0.x + tri.p1.x + tri.p2.x) / 3.0f > 1.5f ? 1 : 0;  // the strip sits at x = 3
    const TriangleShading &g = given.triangle_shading[i], &m = made.triangle_shading[i];
    const glm::vec3 gt[3] = {g.tangent0, g.tangent1, g.tangent2}, mt[3] = {m.tangent0, m.tangent1, m.tangent2};
    const float gh[3] = {g.handedness0, g.handedness1, g.handedness2}, mh[3] = {m.handedness0, m.handedness1, m.handedness2};
    for (int k = 0; k < 3; ++k) {
      INFO("triangle " << i << " corner " << k);
      CHECK(mh[k] == gh[k]);
      const double c = glm::dot(glm::normalize(glm::dvec3(gt[k])), glm::normalize(glm::dvec3(mt[k])));
      worst[strip] = std::max(worst[strip], std::acos(std::clamp(c, -1.0, 1.0)));
      ++corners[strip];
    }
  }
  INFO("worst angle between ours and Blender's tangent: sphere " << worst[0] << " rad over " << corners[0]
                                                                 << " corners, strip " << worst[1] << " rad over "
                                                                 << corners[1]);
  CHECK(corners[0] == 3 * 64);
  CHECK(worst[0] < 1e-4);
  CHECK(worst[1] < 5e-3);
}

TEST_CASE("normal maps: a vertex no triangle with UV area touches keeps its triangle's tangent from the UVs",
          "[shading_normals][gltf]") {
  // One triangle with UV area and one without, sharing an edge.
  const std::vector<glm::vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  const std::vector<glm::vec3> n(4, glm::vec3(0, 0, 1));
  const std::vector<glm::vec2> uv = {{0, 1}, {1, 1}, {0, 0}, {0.5f, 0.5f}};
  std::vector<glm::vec4> t = gltf::vertex_tangents(p, n, uv, {0, 1, 2, 1, 3, 2});
  for (int i = 0; i < 3; ++i) CHECK(glm::length(glm::vec3(t[i]) - glm::vec3(1, 0, 0)) < 1e-6f);
  for (int i = 0; i < 3; ++i) CHECK(t[i].w == 1.0f);  // bitangent cross(n, t) = +y runs along -dP/dv
  CHECK(t[3] == glm::vec4(0.0f));
}
