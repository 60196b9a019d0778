// Tests of the glTF loader (the contract (README.md) "Scenes"; common/scene/gltf_loader.cpp): each rule on a
// small fixture from tests/data/gltf (written by make_fixtures.py), and each kind of
// malformed file turned into pt::Error with exit code 3 and a one-line message.
#include <catch2/catch.hpp>

#include <unistd.h>  // dup, dup2: capturing stderr

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string>

#include "common/base/error.h"
#include "common/scene/scene_loading.h"

namespace {

std::string fixture(const std::string& name) { return std::string(PT_TEST_DATA_DIR) + "/gltf/" + name; }

pt::Scene load(const std::string& name) { return pt::load_gltf(fixture(name)); }

void check_point(glm::vec3 got, glm::vec3 want) {
  INFO("got (" << got.x << ", " << got.y << ", " << got.z << "), want (" << want.x << ", " << want.y << ", "
               << want.z << ")");
  CHECK(got.x == Approx(want.x).margin(1e-5));
  CHECK(got.y == Approx(want.y).margin(1e-5));
  CHECK(got.z == Approx(want.z).margin(1e-5));
}

void check_triangle(const pt::Triangle& t, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  check_point(t.p0, a);
  check_point(t.p1, b);
  check_point(t.p2, c);
}

// The material of the triangle whose first vertex has this x (fixtures place one
// triangle per material along x).
const pt::Material& material_at(const pt::Scene& scene, float x) {
  for (const pt::Triangle& t : scene.triangles) {
    if (t.p0.x == x) return scene.materials.at(t.material);
  }
  FAIL("no triangle at x = " << x);
  throw 0;
}

// The loader's failure on a fixture: the exit code and one-line message it carries.
void require_bad_scene(const std::string& path, std::initializer_list<const char*> words) {
  int code = 0;
  std::string message;
  try {
    pt::load_gltf(path);
  } catch (const pt::Error& e) {
    code = e.code();
    message = e.what();
  }
  INFO("message: " << message);
  REQUIRE(code == pt::kExitBadScene);
  CHECK(message.find('\n') == std::string::npos);
  for (const char* word : words) CHECK_THAT(message, Catch::Contains(word));
}

// Collects what is written to stderr (file descriptor 2) while it lives.
class StderrCapture {
 public:
  StderrCapture() : file_(std::tmpfile()) {
    std::fflush(stderr);
    saved_ = dup(2);
    dup2(fileno(file_), 2);
  }
  ~StderrCapture() { restore(); }
  std::string text() {
    restore();
    std::rewind(file_);
    std::string out;
    for (int c; (c = std::fgetc(file_)) != EOF;) out += char(c);
    return out;
  }

 private:
  void restore() {
    if (saved_ < 0) return;
    std::fflush(stderr);
    dup2(saved_, 2);
    close(saved_);
    saved_ = -1;
  }
  std::FILE* file_;
  int saved_ = -1;
};

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

int count(const std::string& text, const std::string& word) {
  int n = 0;
  for (std::size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) ++n;
  return n;
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
  CHECK(m.kind == pt::kMaterialDiffuse);  // the texture is ignored, the factors kept
  check_point(m.base_color, {1, 1, 1});
}

TEST_CASE(
    "a Blender-like file with textures, animation, skin, morph targets, lines and an unknown "
    "extension loads its triangles and names each unmodelled feature once",
    "[loader]") {
  StderrCapture capture;
  pt::Scene scene = load("blender_like.gltf");
  load("blender_like.gltf");
  std::string err = capture.text();
  INFO("stderr: " << err);
  REQUIRE(scene.triangles.size() == 1);  // the line primitive is not drawn
  check_triangle(scene.triangles[0], {10, 0, 0}, {12, 0, 0}, {10, 2, 0});
  const pt::Material& m = scene.materials.at(scene.triangles[0].material);
  CHECK(m.kind == pt::kMaterialDiffuse);
  for (const char* word :
       {"textures", "animations", "skins", "morph targets", "mode 1", "EXT_made_up_extension"}) {
    CHECK(count(err, word) == 1);
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

// --- Materials ------------------------------------------------------------------------

TEST_CASE("metallic-roughness factors become the contract's materials", "[loader]") {
  pt::Scene scene = load("materials.gltf");  // triangle i at x = 2i
  SECTION("metallic 0 is Lambertian with the base colour as albedo") {
    const pt::Material& m = material_at(scene, 0);
    CHECK(m.kind == pt::kMaterialDiffuse);
    check_point(m.base_color, {0.8f, 0.2f, 0.1f});
  }
  SECTION("metallic 1 with roughness 0 is a mirror") {
    CHECK(material_at(scene, 2).kind == pt::kMaterialMirror);
  }
  SECTION("metallic 1 with roughness 0.5 is GGX with alpha = roughness^2") {
    const pt::Material& m = material_at(scene, 4);
    CHECK(m.kind == pt::kMaterialConductor);
    CHECK(m.alpha == Approx(0.25f));
    check_point(m.base_color, {0.95f, 0.64f, 0.54f});
  }
  SECTION("metallic between 0 and 1 mixes conductor and diffuse") {
    const pt::Material& m = material_at(scene, 6);
    CHECK(m.kind == pt::kMaterialMixed);
    CHECK(m.metallic == Approx(0.25f));
    CHECK(m.alpha == Approx(0.16f));
  }
  SECTION("transmission is glass with ior 1.5 by default") {
    const pt::Material& m = material_at(scene, 8);
    CHECK(m.kind == pt::kMaterialGlass);
    CHECK(m.ior == Approx(1.5f));
  }
  SECTION("KHR_materials_ior sets the glass's ior; the base colour tints it") {
    const pt::Material& m = material_at(scene, 10);
    CHECK(m.kind == pt::kMaterialGlass);
    CHECK(m.ior == Approx(1.33f));
    check_point(m.base_color, {0.9f, 1.0f, 0.9f});
  }
  SECTION("emission is emissiveFactor times emissiveStrength, front face only") {
    const pt::Material& m = material_at(scene, 12);
    check_point(m.emission, {4.0f, 2.0f, 1.0f});
    CHECK(m.double_sided == 0u);
  }
  SECTION("doubleSided emits from both faces") {
    const pt::Material& m = material_at(scene, 14);
    check_point(m.emission, {1.0f, 1.0f, 1.0f});
    CHECK(m.double_sided == 1u);
    CHECK(m.kind == pt::kMaterialDiffuse);
  }
  SECTION("no material is glTF's default: base colour 1, metallic 1, roughness 1") {
    const pt::Material& m = material_at(scene, 16);
    CHECK(m.kind == pt::kMaterialConductor);
    CHECK(m.alpha == Approx(1.0f));
    check_point(m.base_color, {1, 1, 1});
  }
  SECTION("each material used is added once; unused ones are not") {
    REQUIRE(scene.triangles.size() == 10);
    CHECK(scene.triangles[9].material == scene.triangles[0].material);
    CHECK(scene.materials.size() == 9);
  }
}

// --- Lights ---------------------------------------------------------------------------

TEST_CASE("KHR_lights_punctual point lights sit at their node with intensity times colour", "[loader]") {
  pt::Scene scene = load("point_light.gltf");  // a spot and a directional light are skipped
  REQUIRE(scene.point_lights.size() == 2);
  check_point(scene.point_lights[0].position, {1, 2, 0});
  check_point(scene.point_lights[0].intensity, {5, 10, 2.5f});
  check_point(scene.point_lights[1].position, {0, 0, -4});
  check_point(scene.point_lights[1].intensity, {3, 3, 3});  // colour defaults to white
}

// --- Malformed files --------------------------------------------------------------------

TEST_CASE("a missing file is an error that names it", "[loader]") {
  require_bad_scene(fixture("no_such_scene.gltf"), {"no_such_scene.gltf", "no such file"});
}

TEST_CASE("a file that is neither .gltf nor .glb is an error", "[loader]") {
  require_bad_scene(fixture("scene.obj"), {"scene.obj", ".gltf or .glb"});
}

TEST_CASE("invalid JSON is an error", "[loader]") {
  require_bad_scene(fixture("bad_json.gltf"), {"bad_json.gltf:", "invalid JSON"});
}

TEST_CASE("tinygltf's own parse errors become one line", "[loader]") {
  require_bad_scene(fixture("tinygltf_error.gltf"), {"tinygltf_error.gltf:", "'type'"});
}

TEST_CASE("an accessor running past its bufferView is an error", "[loader]") {
  require_bad_scene(fixture("accessor_past_view.gltf"),
                    {"accessors[0] (POSITION of meshes[0].primitives[0])", "runs past bufferViews[0]",
                     "needs 480 bytes, has 36", "re-export"});
}

TEST_CASE("a bufferView running past its buffer is an error", "[loader]") {
  require_bad_scene(fixture("view_past_buffer.gltf"),
                    {"bufferViews[0]", "runs past buffers[0]", "needs 44 bytes, has 40"});
}

TEST_CASE("an accessor byteOffset near 2^64 does not wrap around", "[loader]") {
  require_bad_scene(fixture("accessor_offset_2_64.gltf"), {"runs past bufferViews[0]", "overflow"});
}

TEST_CASE("a bufferView byteOffset near 2^64 does not wrap around", "[loader]") {
  require_bad_scene(fixture("view_offset_2_64.gltf"), {"runs past buffers[0]", "overflow"});
}

TEST_CASE("an accessor with count 0 is an error", "[loader]") {
  require_bad_scene(fixture("count_zero.gltf"), {"accessors[0]", "count 0"});
}

TEST_CASE("an index past the vertex count is an error", "[loader]") {
  require_bad_scene(fixture("index_past_vertices.gltf"),
                    {"indices of meshes[0].primitives[0]", "is 7", "vertex count (3)"});
}

TEST_CASE("a material index out of range is an error", "[loader]") {
  require_bad_scene(fixture("material_out_of_range.gltf"),
                    {"meshes[0].primitives[0].material = 5", "out of range"});
}

TEST_CASE("a mesh index out of range is an error", "[loader]") {
  require_bad_scene(fixture("mesh_out_of_range.gltf"), {"nodes[0].mesh = 3", "out of range"});
}

TEST_CASE("a node index out of range is an error", "[loader]") {
  require_bad_scene(fixture("node_out_of_range.gltf"), {"nodes[0].children[0] = 9", "out of range"});
}

TEST_CASE("an index too large for an int is an error, not truncated", "[loader]") {
  require_bad_scene(fixture("index_too_large.gltf"), {"nodes[0].mesh = 4294967296", "out of range"});
}

TEST_CASE("a node that is its own child is an error", "[loader]") {
  require_bad_scene(fixture("node_own_child.gltf"), {"nodes[0] is its own child", "cycle"});
}

TEST_CASE("a cycle through two nodes is an error", "[loader]") {
  require_bad_scene(fixture("node_cycle.gltf"), {"own ancestor", "cycle"});
}

TEST_CASE("a NaN position is an error", "[loader]") {
  require_bad_scene(fixture("nan_position.gltf"), {"vertex 1", "not finite", "nan"});
}

TEST_CASE("an infinite position is an error", "[loader]") {
  require_bad_scene(fixture("inf_position.gltf"), {"vertex 2", "not finite", "inf"});
}

TEST_CASE("a translation that is infinite as a 32-bit float is an error", "[loader]") {
  require_bad_scene(fixture("huge_translation.gltf"), {"nodes[0].translation[0]", "not a finite"});
}

TEST_CASE("a required extension that is not supported is an error naming it", "[loader]") {
  require_bad_scene(fixture("required_extension.gltf"), {"extensionsRequired", "KHR_draco_mesh_compression"});
}

TEST_CASE("positions that are not 32-bit floats are an error", "[loader]") {
  require_bad_scene(fixture("position_not_float.gltf"), {"POSITION", "VEC3 of FLOAT"});
}

TEST_CASE("buffer URIs may not leave the scene's folder", "[loader]") {
  for (const char* name : {"uri_dotdot.gltf", "uri_absolute.gltf", "uri_encoded_dotdot.gltf"}) {
    INFO(name);
    require_bad_scene(fixture(name), {"buffers[0].uri", "outside the scene's folder"});
  }
}

TEST_CASE("an image whose bufferView runs past its buffer is an error", "[loader]") {
  require_bad_scene(fixture("image_view_past_buffer.gltf"),
                    {"images[0]", "runs past buffers[0]", "needs 1036 bytes, has 44"});
}

TEST_CASE("a .glb whose BIN chunk runs past the end of the file is an error", "[loader]") {
  require_bad_scene(fixture("truncated.glb"), {"truncated.glb:", "BIN chunk"});
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
  check_point(scene.point_lights[0].intensity, {20, 18, 16});
  CHECK(scene.camera.has_value());
}
