// Tests of what the glTF loader draws (the contract (README.md) "Scenes", Geometry; common/scene/
// gltf_primitives.cpp): strips and fans as the triangles of the equivalent list with the same
// winding, points and lines counted and skipped, a file with no triangle refused, EXT_mesh_gpu_instancing's
// instances placed and counted in the triangle budget, and the scene chosen. Not part of the article.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/gtc/constants.hpp>

#include "common/base/error.h"
#include "common/scene/scene_loading.h"
#include "common/scene/scene_sanity.h"
#include "tests/common/scene/gltf_draw_files.h"
#include "tests/support/gltf_checks.h"
#include "tests/support/stderr_capture.h"

using namespace pt::test;

namespace test_gltf_draws {  // this file's names: the unity build compiles it with others (tests/CMakeLists.txt)

namespace {

std::filesystem::path dir() { return std::filesystem::temp_directory_path() / "pt_test_gltf_draws"; }

using Tri = std::array<glm::vec3, 3>;

bool less(glm::vec3 a, glm::vec3 b) { return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.z < b.z; }

// The scene's triangles, each turned (keeping its winding) to start at its least vertex, sorted:
// two scenes with the same list have the same triangles and front faces.
std::vector<Tri> canonical(const pt::Scene& scene) {
  std::vector<Tri> out;
  for (const pt::Triangle& t : scene.triangles) {
    Tri v = {t.p0, t.p1, t.p2};
    while (less(v[1], v[0]) || less(v[2], v[0])) std::rotate(v.begin(), v.begin() + 1, v.end());
    out.push_back(v);
  }
  std::sort(out.begin(), out.end(), [](const Tri& a, const Tri& b) {
    for (int k = 0; k < 3; ++k) {
      if (a[k] != b[k]) return less(a[k], b[k]);
    }
    return false;
  });
  return out;
}

std::string one_mesh(const std::string& name, const std::vector<glm::vec3>& points, int mode, int indices = -1) {
  DrawFile f;
  f.scene({f.node({{"mesh", f.mesh(points, mode, indices)}})});
  return f.write(dir(), name);
}

std::string with_indices(const std::string& name, const std::vector<glm::vec3>& points, int mode,
                         const std::vector<std::uint16_t>& indices) {
  DrawFile f;
  int accessor = f.u16s(indices);
  f.scene({f.node({{"mesh", f.mesh(points, mode, accessor)}})});
  return f.write(dir(), name);
}

// A zig-zag strip of 6 vertices and a fan of 5 around the origin, both facing +z, and their lists.
const std::vector<glm::vec3> kStrip = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 2, 0}, {1, 2, 0}};
const std::vector<glm::vec3> kFan = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {-1, 1, 0}};

std::vector<glm::vec3> strip_as_list() {
  const auto& v = kStrip;
  return {v[0], v[1], v[2], v[2], v[1], v[3], v[2], v[3], v[4], v[4], v[3], v[5]};
}
std::vector<glm::vec3> fan_as_list() {
  const auto& v = kFan;
  return {v[0], v[1], v[2], v[0], v[2], v[3], v[0], v[3], v[4]};
}

void check_front_faces_up(const pt::Scene& scene) {
  for (const pt::Triangle& t : scene.triangles) CHECK(glm::cross(t.p1 - t.p0, t.p2 - t.p0).z > 0.0f);
}

}  // namespace

TEST_CASE("a triangle strip gives the triangles and winding of the equivalent list", "[loader][draws]") {
  pt::Scene list = pt::load_gltf(one_mesh("strip_list", strip_as_list(), 4));
  pt::Scene strip = pt::load_gltf(one_mesh("strip", kStrip, 5));
  REQUIRE(strip.triangles.size() == 4);
  CHECK(canonical(strip) == canonical(list));
  check_front_faces_up(list);
  check_front_faces_up(strip);
}

TEST_CASE("an indexed strip with a join gives the triangles of the list", "[loader][draws]") {
  // The vertices stored backwards, drawn by indices; two strips joined by repeated indices
  // (the triangles that name a vertex twice have no area and are left out silently).
  std::vector<glm::vec3> backwards(kStrip.rbegin(), kStrip.rend());
  std::vector<std::uint16_t> indices = {5, 4, 3, 2, 1, 0};
  pt_test::StderrCapture err;
  pt::Scene strip = pt::load_gltf(with_indices("strip_indexed", backwards, 5, indices));
  REQUIRE(strip.triangles.size() == 4);
  CHECK(canonical(strip) == canonical(pt::load_gltf(one_mesh("strip_list2", strip_as_list(), 4))));

  // Vertices 0 1 2 2 2 3 4 5: the triangle (0 1 2), three joins, then (2 3 4) and (3 5 4).
  std::vector<std::uint16_t> joined = {5, 4, 3, 3, 3, 2, 1, 0};
  pt::Scene two = pt::load_gltf(with_indices("strip_joined", backwards, 5, joined));
  CHECK(two.triangles.size() == 3);
  CHECK(two.degenerate_triangles == 0);
  CHECK(err.text().find("degenerate") == std::string::npos);
  check_front_faces_up(two);
}

TEST_CASE("a triangle fan gives the triangles and winding of the equivalent list", "[loader][draws]") {
  pt::Scene list = pt::load_gltf(one_mesh("fan_list", fan_as_list(), 4));
  pt::Scene fan = pt::load_gltf(one_mesh("fan", kFan, 6));
  REQUIRE(fan.triangles.size() == 3);
  CHECK(canonical(fan) == canonical(list));
  check_front_faces_up(fan);
  pt::Scene indexed = pt::load_gltf(with_indices("fan_indexed", kFan, 6, {0, 1, 2, 3, 4}));
  CHECK(canonical(indexed) == canonical(list));
}

TEST_CASE("a file of only lines is refused with the counts", "[loader][draws]") {
  DrawFile f;
  const std::vector<glm::vec3> segment = {{0, 0, 0}, {1, 0, 0}};
  int lines = f.mesh(segment, 1);
  f.doc["meshes"][lines]["primitives"].push_back(f.doc["meshes"][lines]["primitives"][0]);
  f.doc["meshes"][lines]["primitives"].push_back(f.doc["meshes"][lines]["primitives"][0]);
  f.scene({f.node({{"mesh", lines}}), f.node({{"mesh", f.mesh(segment, 0)}})});
  require_bad_scene(f.write(dir(), "only_lines"),
                    {"no triangles to draw: ", "1 primitive of mode POINTS", "3 primitives of mode LINES skipped"});
}

TEST_CASE("points and lines beside triangles are skipped with one line of counts", "[loader][draws]") {
  DrawFile f;
  f.scene({f.node({{"mesh", f.mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, 4)}}),
           f.node({{"mesh", f.mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}, 3)}})});
  std::string path = f.write(dir(), "lines_and_triangles");
  pt_test::StderrCapture err;
  pt::Scene scene = pt::load_gltf(path);
  std::string text = err.text();
  CHECK(scene.triangles.size() == 1);
  CHECK(text.find("1 primitive of mode LINE_STRIP skipped (points and lines are not drawn)") != std::string::npos);
  CHECK(std::count(text.begin(), text.end(), '\n') == 1);
}

namespace {

// One triangle, instanced 3 times by a node translated by (0, 0, 10): instance 1 is moved
// by (5, 0, 0) and turned 90 degrees about z, instance 2 moved by (0, 5, 0) and scaled by 2.
std::string instanced_file() {
  DrawFile f;
  int mesh = f.mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, 4);
  const float h = std::sqrt(0.5f);
  int t = f.vec3s({{0, 0, 0}, {5, 0, 0}, {0, 5, 0}});
  int r = f.vec4s({{0, 0, 0, 1}, {0, 0, h, h}, {0, 0, 0, 1}});
  int s = f.vec3s({{1, 1, 1}, {1, 1, 1}, {2, 2, 2}});
  f.scene({f.node({{"mesh", mesh},
                   {"translation", {0, 0, 10}},
                   {"extensions",
                    {{"EXT_mesh_gpu_instancing", {{"attributes", {{"TRANSLATION", t}, {"ROTATION", r}, {"SCALE", s}}}}}}}})});
  f.doc["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
  return f.write(dir(), "instanced");
}

}  // namespace

TEST_CASE("EXT_mesh_gpu_instancing draws the mesh once per instance, each in the node's space", "[loader][draws]") {
  pt_test::StderrCapture err;
  pt::Scene scene = pt::load_gltf(instanced_file());
  CHECK(err.text().find("EXT_mesh_gpu_instancing") == std::string::npos);  // no "not modelled"
  REQUIRE(scene.triangles.size() == 3);
  check_triangle(scene.triangles[0], {0, 0, 10}, {1, 0, 10}, {0, 1, 10});
  check_triangle(scene.triangles[1], {5, 0, 10}, {5, 1, 10}, {4, 0, 10});
  check_triangle(scene.triangles[2], {0, 5, 10}, {2, 5, 10}, {0, 7, 10});
}

TEST_CASE("the triangle budget counts every instance", "[loader][draws]") {
  const std::string path = instanced_file();
  pt::set_scene_memory_budget(2 * pt::kSceneBytesPerTriangle + 100);  // room for 2 triangles, not 3
  int code = 0;
  std::string message;
  try {
    pt::load_gltf(path);
  } catch (const pt::Error& e) {
    code = e.code(), message = e.what();
  }
  pt::set_scene_memory_budget(0);
  INFO(message);
  CHECK(code == pt::kExitBadScene);
  CHECK(message.find("place 3 triangles") != std::string::npos);
}

TEST_CASE("the file's scene is drawn, --gltf-scene picks another, and a missing one is named", "[loader][draws]") {
  DrawFile f;
  f.scene({f.node({{"mesh", f.mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, 4)}})}, "Main");
  f.scene({f.node({{"mesh", f.mesh({{0, 7, 0}, {1, 7, 0}, {0, 8, 0}}, 4)}})}, "Other");
  f.doc["scene"] = 1;
  const std::string path = f.write(dir(), "two_scenes");
  {
    pt_test::StderrCapture err;
    pt::Scene scene = pt::load_gltf(path);
    REQUIRE(scene.triangles.size() == 1);
    CHECK(scene.triangles[0].p0.y == 7.0f);
    CHECK(err.text().find("the file has 2 scenes; drawing scene 1 'Other' (--gltf-scene N|NAME picks another)") !=
          std::string::npos);
  }
  CHECK(pt::load_gltf(path, "0").triangles[0].p0.y == 0.0f);
  CHECK(pt::load_gltf(path, "Main").triangles[0].p0.y == 0.0f);
  int code = 0;
  std::string message;
  try {
    pt::load_gltf(path, "Nope");
  } catch (const pt::Error& e) {
    code = e.code(), message = e.what();
  }
  CHECK(code == pt::kExitBadOption);
  CHECK(message.find("--gltf-scene Nope: ") == 0);
  CHECK(message.find("its scenes: 0 'Main', 1 'Other'") != std::string::npos);
}

}  // namespace test_gltf_draws
