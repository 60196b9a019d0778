// Tests of the glTF loader (the contract (README.md) "Scenes"; common/scene/gltf_loader.cpp): the
// geometry and the camera each rule gives on a small fixture from tests/data/gltf (written
// by make_fixtures.py), and the shipped scenes. Materials and lights: test_gltf_materials.cpp;
// malformed files: test_gltf_malformed.cpp.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/support/cli_run.h"
#include "tests/support/gltf_checks.h"
#include "tests/support/stderr_capture.h"

using namespace pt::test;

namespace test_gltf_loader {  // this file's names: the unity build compiles it with others (tests/CMakeLists.txt)

namespace {

// Collects what is written to stderr (file descriptor 2) while it lives.

void append_u32(std::string& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out += char(v >> (8 * i) & 0xff);
}

// A .glb too large to ship (786 KB): a quad drawn by 32-bit indices from vertices
// 65536..65539, so that every byte of an index matters. Returns its path.
std::string write_u32_index_glb() {
  const std::uint32_t kVertices = 65540;
  std::string bin;
  for (std::uint32_t i = 0; i < kVertices; ++i) {
    float quad[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    for (int k = 0; k < 3; ++k) {
      float f = i >= 65536 ? quad[i - 65536][k] : 9.0f;
      std::uint32_t bits;
      std::memcpy(&bits, &f, 4);
      append_u32(bin, bits);
    }
  }
  std::size_t position_bytes = bin.size();
  for (std::uint32_t index : {65536, 65537, 65538, 65536, 65538, 65539}) append_u32(bin, index);
  std::ostringstream json;
  json << R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
       << R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
       << R"("accessors":[{"bufferView":0,"componentType":5126,"count":)" << kVertices
       << R"(,"type":"VEC3"},)"
       << R"({"bufferView":1,"componentType":5125,"count":6,"type":"SCALAR"}],)"
       << R"("bufferViews":[{"buffer":0,"byteLength":)" << position_bytes << "},"
       << R"({"buffer":0,"byteOffset":)" << position_bytes << R"(,"byteLength":24}],)"
       << R"("buffers":[{"byteLength":)" << bin.size() << "}]}";
  std::string text = json.str();
  text.append((4 - text.size() % 4) % 4, ' ');
  std::string glb = "glTF";
  append_u32(glb, 2);
  append_u32(glb, std::uint32_t(12 + 8 + text.size() + 8 + bin.size()));
  append_u32(glb, std::uint32_t(text.size()));
  append_u32(glb, 0x4E4F534Au);  // JSON
  glb += text;
  append_u32(glb, std::uint32_t(bin.size()));
  append_u32(glb, 0x004E4942u);  // BIN
  glb += bin;
  std::string path = (std::filesystem::temp_directory_path() / "pt_test_u32_indices.glb").string();
  std::ofstream(path, std::ios::binary) << glb;
  return path;
}

}  // namespace

// --- Geometry ---------------------------------------------------------------------------

TEST_CASE("a triangle under a translated, rotated and scaled parent and child lands where computed by hand",
          "[loader]") {
  // parent T(1,2,3) R(90 deg about z) S(2), child T(0,0,-1) S(1,3,1)
  for (const char* name : {"transform_trs.gltf", "transform_matrix.gltf"}) {
    INFO(name);
    pt::Scene scene = load(name);
    REQUIRE(scene.triangles.size() == 1);
    check_triangle(scene.triangles[0], {1, 2, 1}, {1, 4, 1}, {-5, 2, 1});
    CHECK(scene.degenerate_triangles == 0);
  }
}

TEST_CASE("indexed primitives read unsigned byte, short and int indices", "[loader]") {
  // the same quad, from vertices 0..3 (u8, non-indexed), 256..259 (u16, u32) and 65536..65539
  for (std::string path : {fixture("indices_u8.gltf"), fixture("indices_u16.gltf"),
                           fixture("indices_u32.gltf"), fixture("non_indexed.gltf"), write_u32_index_glb()}) {
    INFO(path);
    pt::Scene scene = pt::load_gltf(path);
    REQUIRE(scene.triangles.size() == 2);
    check_triangle(scene.triangles[0], {0, 0, 0}, {1, 0, 0}, {1, 1, 0});
    check_triangle(scene.triangles[1], {0, 0, 0}, {1, 1, 0}, {0, 1, 0});
  }
}

TEST_CASE("interleaved vertices honour byteStride and the accessor's byteOffset", "[loader]") {
  pt::Scene scene = load("interleaved.gltf");
  REQUIRE(scene.triangles.size() == 1);
  check_triangle(scene.triangles[0], {2, 0, 0}, {3, 0, 0}, {2, 1, 0});
}

TEST_CASE("triangles without area are counted and skipped", "[loader]") {
  pt::Scene scene = load("degenerate.gltf");
  CHECK(scene.triangles.size() == 1);
  CHECK(scene.degenerate_triangles == 3);
}

TEST_CASE("the default scene is drawn; with no scenes every root node is", "[loader]") {
  pt::Scene chosen = load("default_scene.gltf");  // "scene": 1 holds only the node at y = 7
  REQUIRE(chosen.triangles.size() == 1);
  check_triangle(chosen.triangles[0], {0, 7, 0}, {1, 7, 0}, {0, 8, 0});

  pt::Scene all = load("no_scenes.gltf");  // two roots, one with a child
  REQUIRE(all.triangles.size() == 3);
  check_point(all.triangles[0].p0, {0, 0, 0});
  check_point(all.triangles[1].p0, {0, 0, 1});
  check_point(all.triangles[2].p0, {5, 0, 0});
}

TEST_CASE("a buffer in a separate .bin next to the .gltf is read", "[loader]") {
  pt::Scene scene = load("separate_bin.gltf");
  REQUIRE(scene.triangles.size() == 1);
  check_triangle(scene.triangles[0], {0, 0, 2}, {1, 0, 2}, {0, 1, 2});
}

TEST_CASE("a binary .glb with an embedded image loads its geometry and camera", "[loader]") {
  pt::Scene scene = load("textured.glb");
  REQUIRE(scene.triangles.size() == 1);
  check_triangle(scene.triangles[0], {0, 0, 1}, {1, 0, 1}, {0, 1, 1});
  REQUIRE(scene.camera.has_value());
  CHECK(scene.camera->yfov == Approx(0.8f));
  check_point(scene.camera->to_world[3], {0, 0, 5});
  const pt::Material& m = scene.materials.at(scene.triangles[0].material);
  CHECK(m.kind == pt::kMaterialDielectric);  // the factors in the material, the texture beside it
  check_point(m.base_color, {1, 1, 1});
  REQUIRE(scene.textures.size() == 1);  // decoded by OpenImageIO (test_gltf_textures.cpp)
  CHECK(scene.material_textures.at(scene.triangles[0].material).base_color == 0u);
}

TEST_CASE(
    "a Blender-like file with textures, animation, skin, morph targets, lines and an unknown "
    "extension loads its triangles and names each unmodelled feature once",
    "[loader]") {
  pt_test::StderrCapture capture;
  pt::Scene scene = load("blender_like.gltf");
  load("blender_like.gltf");
  std::string err = capture.text();
  INFO("stderr: " << err);
  REQUIRE(scene.triangles.size() == 1);  // the line primitive is not drawn
  check_triangle(scene.triangles[0], {10, 0, 0}, {12, 0, 0}, {10, 2, 0});
  const pt::Material& m = scene.materials.at(scene.triangles[0].material);
  CHECK(m.kind == pt::kMaterialDielectric);  // metallic 0: glTF's specular layer over a base
  CHECK(err.find("normal textures") == std::string::npos);  // modelled (docs/shading_normals.md)
  for (const char* word :
       {"animations", "skins", "morph targets", "mode LINES", "EXT_made_up_extension"}) {
    CHECK(pt_test::occurrences(err, word) == 1);
  }
}

// --- Camera ---------------------------------------------------------------------------

TEST_CASE("the first camera met depth first is perspective with its yfov and node transform", "[loader]") {
  // scene nodes: [triangle, parent T(0,1,5) -> child R(90 deg about y) with perspective, orthographic]
  pt::Scene scene = load("camera_perspective.gltf");
  REQUIRE(scene.camera.has_value());
  CHECK(scene.camera->kind == pt::kCameraPerspective);
  CHECK(scene.camera->yfov == Approx(0.5f));
  check_point(scene.camera->to_world[3], {0, 1, 5});
  check_point(scene.camera->to_world[2], {1, 0, 0});   // the camera's +Z; it looks down -Z = -x
  check_point(scene.camera->to_world[0], {0, 0, -1});  // its +X
}

TEST_CASE("an orthographic camera keeps xmag and ymag as half-extents", "[loader]") {
  pt::Scene scene = load("camera_orthographic.gltf");
  REQUIRE(scene.camera.has_value());
  CHECK(scene.camera->kind == pt::kCameraOrthographic);
  CHECK(scene.camera->xmag == Approx(2.0f));
  CHECK(scene.camera->ymag == Approx(1.5f));
  check_point(scene.camera->to_world[3], {0, 0, 10});
}

TEST_CASE("a file without a camera leaves the scene's camera empty", "[loader]") {
  CHECK_FALSE(load("transform_trs.gltf").camera.has_value());
}

// --- Shipped scenes ---------------------------------------------------------------------

namespace {
std::string shipped(const std::string& name) {
  return std::string(PT_TEST_DATA_DIR) + "/../../scenes/" + name;
}
}  // namespace

// Whether two triangles have the same corners in the same turning order (the same
// front face) and materials of the same kind, colour and emission.
bool same_triangle(const pt::Scene& sa, const pt::Triangle& a, const pt::Scene& sb, const pt::Triangle& b) {
  const glm::vec3 pa[3] = {a.p0, a.p1, a.p2}, pb[3] = {b.p0, b.p1, b.p2};
  const pt::Material &ma = sa.materials[a.material], &mb = sb.materials[b.material];
  if (ma.kind != mb.kind || glm::distance(ma.base_color, mb.base_color) > 1e-5f ||
      glm::distance(ma.emission, mb.emission) > 1e-4f) {
    return false;
  }
  for (int r = 0; r < 3; ++r) {
    bool all = true;
    for (int k = 0; k < 3; ++k) all = all && glm::distance(pa[k], pb[(k + r) % 3]) < 1e-5f;
    if (all) return true;
  }
  return false;
}

TEST_CASE("scenes/cornell.gltf is builtin:cornell as a file", "[loader]") {
  pt::Scene file = pt::load_gltf(shipped("cornell.gltf"));
  pt::Scene builtin = pt::make_builtin_scene("cornell");
  REQUIRE(file.triangles.size() == builtin.triangles.size());
  for (const pt::Triangle& b : builtin.triangles) {
    INFO("builtin triangle at (" << b.p0.x << ", " << b.p0.y << ", " << b.p0.z << ")");
    CHECK(std::any_of(file.triangles.begin(), file.triangles.end(),
                      [&](const pt::Triangle& a) { return same_triangle(file, a, builtin, b); }));
  }
  REQUIRE(file.camera.has_value());
  CHECK(file.camera->yfov == Approx(builtin.camera->yfov));
  check_point(file.camera->to_world[3], glm::vec3(builtin.camera->to_world[3]));
}

TEST_CASE("scenes/glossy_glass.gltf has its metal, glass, area light, point light and camera", "[loader]") {
  pt::Scene scene = pt::load_gltf(shipped("glossy_glass.gltf"));
  CHECK(scene.degenerate_triangles == 0);
  int conductors = 0, glass = 0, emitters = 0;
  for (const pt::Material& m : scene.materials) {
    conductors += m.kind == pt::kMaterialConductor && m.alpha == Approx(0.09f);
    glass += m.kind == pt::kMaterialGlass && m.ior == Approx(1.5f);
    emitters += pt::is_emissive(m);
  }
  CHECK(conductors == 1);
  CHECK(glass == 1);
  CHECK(emitters == 1);
  REQUIRE(scene.point_lights.size() == 1);
  check_point(scene.point_lights[0].intensity, {20, 18, 16});  // 13660 cd x its colour, at 683 lm/W
  CHECK(scene.camera.has_value());
}

}  // namespace test_gltf_loader
