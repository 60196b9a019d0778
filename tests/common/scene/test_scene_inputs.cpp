// The glTF loader against hostile scene input (issue 45; docs/reliability.md): deep nesting,
// symbolic links out of the scene's folder, emission that overflows floats, cameras and
// scenes that floats cannot resolve, misleading library messages, files that are not
// regular or too large, and instancing beyond the memory. Each is one line and exit 3.
// Not part of the article: the loader's robustness (the contract (README.md) "Scenes").
#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "common/scene/scene_sanity.h"
#include "tests/support/cli_run.h"
#include "tests/support/gltf_checks.h"

namespace fs = std::filesystem;
using Json = nlohmann::json;
using namespace pt::test;

namespace test_scene_inputs {  // this file's names: the unity build compiles it with others (tests/CMakeLists.txt)

namespace {

// A fresh folder for one test case (removed first if an earlier run left it).
fs::path folder(const std::string& name) {
  fs::path dir = pt_test::scratch_dir("pt_scene_inputs") / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// One triangle (0,0,0) (1,0,0) (0,1,0) as 36 bytes of float positions.
std::string triangle_bytes() {
  const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  return std::string(reinterpret_cast<const char*>(p), sizeof p);
}

void write(const fs::path& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

// A scene of that triangle whose buffer is `buffer` (a URI and byteLength are set by the caller).
Json triangle_scene(const Json& buffer) {
  return Json{{"asset", {{"version", "2.0"}}},
              {"scene", 0},
              {"scenes", Json::array({Json{{"nodes", {0}}}})},
              {"nodes", Json::array({Json{{"mesh", 0}}})},
              {"meshes", Json::array({Json{{"primitives", Json::array({Json{{"attributes", {{"POSITION", 0}}}}})}}})},
              {"accessors", Json::array({Json{{"bufferView", 0}, {"componentType", 5126}, {"count", 3},
                                               {"type", "VEC3"}, {"min", {0, 0, 0}}, {"max", {1, 1, 0}}}})},
              {"bufferViews", Json::array({Json{{"buffer", 0}, {"byteLength", 36}}})},
              {"buffers", Json::array({buffer})}};
}

const std::string kTriangleUri = "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA";

std::string save(const fs::path& path, const Json& doc) {
  std::ofstream(path) << doc.dump();
  return path.string();
}

// The budget the programs set, for one test case.
struct MemoryBudget {
  explicit MemoryBudget(std::uint64_t bytes) { pt::set_scene_memory_budget(bytes); }
  ~MemoryBudget() { pt::set_scene_memory_budget(0); }
};

}  // namespace

// --- 2: deep nesting ---------------------------------------------------------------------

TEST_CASE("inputs: a size nested 100,000 arrays deep is refused in one line, not a stack overflow",
          "[loader][reliability]") {
  const fs::path dir = folder("deep");
  for (const char* key : {"count", "byteLength", "byteOffset", "byteStride"}) {
    INFO(key);
    Json doc = triangle_scene({{"byteLength", 36}, {"uri", kTriangleUri}});
    Json& owner = std::string(key) == "count" ? doc["accessors"][0] : doc["bufferViews"][0];
    owner[key] = "DEEP";
    std::string text = doc.dump();
    text.replace(text.find("\"DEEP\""), 6, std::string(100000, '[') + std::string(100000, ']'));
    write(dir / "deep.gltf", text);
    require_bad_scene((dir / "deep.gltf").string(), {"nests arrays and objects deeper than 64 levels"});
  }
}

TEST_CASE("inputs: a size of the wrong JSON type is named by its type, never printed", "[loader][reliability]") {
  const fs::path dir = folder("types");
  Json doc = triangle_scene({{"byteLength", 36}, {"uri", kTriangleUri}});
  doc["accessors"][0]["count"] = std::string(100000, 'x');
  require_bad_scene(save(dir / "string.gltf", doc), {"accessors[0].count must be a non-negative integer, is a string"});
  doc["accessors"][0]["count"] = Json::array({Json::array({3})});
  require_bad_scene(save(dir / "array.gltf", doc), {"is an array"});
  doc["accessors"][0]["count"] = -3;
  require_bad_scene(save(dir / "negative.gltf", doc), {"is -3"});
}

// --- 3: the scene's folder, resolved -------------------------------------------------------

TEST_CASE("inputs: a buffer through a symbolic link to a folder outside the scene's is refused",
          "[loader][reliability]") {
  const fs::path dir = folder("link_dir"), outside = folder("link_dir_outside");
  write(outside / "tri.bin", triangle_bytes());
  fs::create_directory_symlink(outside, dir / "elsewhere");
  require_bad_scene(save(dir / "scene.gltf", triangle_scene({{"byteLength", 36}, {"uri", "elsewhere/tri.bin"}})),
                    {"buffers[0].uri 'elsewhere/tri.bin' resolves to", "outside the scene's folder"});
}

TEST_CASE("inputs: a buffer or image that is a symbolic link to a file outside the scene's folder is refused",
          "[loader][reliability]") {
  const fs::path dir = folder("link_file"), outside = folder("link_file_outside");
  write(outside / "tri.bin", triangle_bytes());
  fs::copy_file(fixture("tex_external.png"), outside / "outside.png");
  fs::create_symlink(outside / "tri.bin", dir / "tri.bin");
  require_bad_scene(save(dir / "buffer.gltf", triangle_scene({{"byteLength", 36}, {"uri", "tri.bin"}})),
                    {"buffers[0].uri 'tri.bin' resolves to", "outside the scene's folder"});
  fs::create_symlink(outside / "outside.png", dir / "image.png");
  Json doc = triangle_scene({{"byteLength", 36}, {"uri", kTriangleUri}});
  doc["images"] = Json::array({Json{{"uri", "image.png"}}});
  require_bad_scene(save(dir / "image.gltf", doc), {"images[0].uri 'image.png' resolves to", "outside"});
}

TEST_CASE("inputs: sub/../x.bin and links that stay inside the scene's folder are read", "[loader][reliability]") {
  const fs::path dir = folder("inside");
  fs::create_directory(dir / "sub");
  write(dir / "tri.bin", triangle_bytes());
  fs::create_symlink("tri.bin", dir / "link.bin");
  for (const char* uri : {"sub/../tri.bin", "link.bin", "./sub/../link.bin"}) {
    INFO(uri);
    pt::Scene scene = pt::load_gltf(save(dir / "scene.gltf", triangle_scene({{"byteLength", 36}, {"uri", uri}})));
    CHECK(scene.triangles.size() == 1);
  }
  require_bad_scene(save(dir / "up.gltf", triangle_scene({{"byteLength", 36}, {"uri", "sub/../../tri.bin"}})),
                    {"points outside the scene's folder"});
}

// --- 5: emission that overflows ------------------------------------------------------------

TEST_CASE("inputs: emissiveStrength 3e38 is refused with the value and the limit; 1e18 is taken",
          "[loader][reliability]") {
  const fs::path dir = folder("emission");
  Json doc = triangle_scene({{"byteLength", 36}, {"uri", kTriangleUri}});
  doc["meshes"][0]["primitives"][0]["material"] = 0;
  doc["extensionsUsed"] = {"KHR_materials_emissive_strength"};
  auto material = [](double strength) {
    return Json::array({Json{{"emissiveFactor", {1.0, 0.5, 0.0}},
                             {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", strength}}}}}}});
  };
  doc["materials"] = material(3e38);
  require_bad_scene(save(dir / "hot.gltf", doc), {"materials[0].emissiveFactor[0] x emissiveStrength = 3e+38",
                                                  "above 1e+18"});
  doc["materials"] = material(1e18);
  pt::Scene scene = pt::load_gltf(save(dir / "limit.gltf", doc));
  CHECK(scene.materials.at(0).emission.x == 1e18f);
}

// --- 8: what floats cannot resolve -----------------------------------------------------------

TEST_CASE("inputs: a camera whose node has scale 0 is refused", "[loader][reliability]") {
  const fs::path dir = folder("camera");
  Json doc = triangle_scene({{"byteLength", 36}, {"uri", kTriangleUri}});
  doc["cameras"] = Json::array({Json{{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.1}}}}});
  doc["nodes"].push_back({{"camera", 0}, {"translation", {0.3, 0.3, 3.0}}, {"scale", {0.0, 0.0, 0.0}}});
  doc["scenes"][0]["nodes"].push_back(1);
  require_bad_scene(save(dir / "zero.gltf", doc), {"cameras[0] (placed by nodes[1]) has a degenerate transform"});
  doc["nodes"][1]["scale"] = {1.0, 1.0, 1.0};
  CHECK(pt::load_gltf(save(dir / "one.gltf", doc)).cameras.size() == 1);
}

TEST_CASE("inputs: scenes scaled to 1e30 or 1e-30 are refused with the rule's limits", "[loader][reliability]") {
  const fs::path dir = folder("scale");
  Json doc = triangle_scene({{"byteLength", 36}, {"uri", kTriangleUri}});
  doc["nodes"][0]["scale"] = {1e30, 1e30, 1e30};
  require_bad_scene(save(dir / "huge.gltf", doc), {"coordinates of 1e+30", "beyond the 1e+12"});
  doc["nodes"][0]["scale"] = {1e10, 1e10, 1e10};
  require_bad_scene(save(dir / "large.gltf", doc), {"1e+10 across", "beyond the 1e+09"});
  doc["nodes"][0]["scale"] = {1e-30, 1e-30, 1e-30};
  require_bad_scene(save(dir / "tiny.gltf", doc), {"1e-30 across", "below the 1e-08"});
  doc["nodes"][0]["scale"] = {1e8, 1e-7, 1.0};  // within both limits
  CHECK(pt::load_gltf(save(dir / "fine.gltf", doc)).triangles.size() == 1);
}

// --- 9: messages in the file's terms ---------------------------------------------------------

TEST_CASE("inputs: a byteLength that disagrees with its buffer names both numbers", "[loader][reliability]") {
  const fs::path dir = folder("lengths");
  require_bad_scene(save(dir / "data.gltf", triangle_scene({{"byteLength", 1000000000000000}, {"uri", kTriangleUri}})),
                    {"buffers[0].byteLength is 1000000000000000 but its data: URI holds 36 bytes"});
  write(dir / "long.bin", triangle_bytes() + std::string(1000, 'x'));
  require_bad_scene(save(dir / "long.gltf", triangle_scene({{"byteLength", 36}, {"uri", "long.bin"}})),
                    {"'long.bin' holds 1036 bytes, more than buffers[0].byteLength 36"});
  write(dir / "short.bin", triangle_bytes().substr(0, 20));
  require_bad_scene(save(dir / "short.gltf", triangle_scene({{"byteLength", 36}, {"uri", "short.bin"}})),
                    {"'short.bin' holds 20 bytes, fewer than buffers[0].byteLength 36", "truncated"});
}

TEST_CASE("inputs: a violation of the specification does not say to re-export", "[loader][reliability]") {
  int code = 0;
  std::string message;
  try {
    pt::load_gltf(fixture("mesh_out_of_range.gltf"));
  } catch (const pt::Error& e) {
    code = e.code(), message = e.what();
  }
  INFO(message);
  CHECK(code == pt::kExitBadScene);
  CHECK(message.find("re-export") == std::string::npos);
  CHECK(message.find("glTF 2.0 specification") != std::string::npos);
}

// --- 6: files that are not regular or too large, and instancing --------------------------------

TEST_CASE("inputs: a folder, a device or a sparse file over 1 GiB as scene is refused before it is read",
          "[loader][reliability]") {
  const fs::path dir = folder("files");
  fs::create_directory(dir / "folder.gltf");
  require_bad_scene((dir / "folder.gltf").string(), {"is a folder, not a regular file"});
  fs::create_symlink("/dev/zero", dir / "zero.glb");
  require_bad_scene((dir / "zero.glb").string(), {"is a character device, not a regular file"});
  { std::ofstream(dir / "sparse.gltf") << "{"; }
  fs::resize_file(dir / "sparse.gltf", (std::uint64_t(1) << 30) + 1);  // sparse: no disk space
  require_bad_scene((dir / "sparse.gltf").string(), {"is 1073741825 bytes, more than the 1 GiB"});
  fs::remove(dir / "sparse.gltf");
}

TEST_CASE("cli: a FIFO as scene is refused at once with exit 3", "[loader][reliability]") {
  const fs::path dir = folder("fifo");
  REQUIRE(::mkfifo((dir / "pipe.gltf").c_str(), 0600) == 0);
  // timeout: without the check the program would wait on the FIFO for ever.
  pt_test::Run r = pt_test::run_program("timeout 60 " + std::string(PT_STAGE1_BIN),
                                        "--scene " + (dir / "pipe.gltf").string() + " --out " + (dir / "x.exr").string(),
                                        "", dir);
  pt_test::check_error(r, "stage1_raycast", 3, "is a FIFO (named pipe), not a regular file");
}

namespace {

// `nodes` nodes placing one mesh of `triangles` triangles, all but the first of zero area: a
// sparse POSITION accessor without a bufferView (zeros) with its first three vertices set.
Json instanced_scene(int nodes, int triangles) {
  Json doc = triangle_scene({{"byteLength", 48}, {"uri", "data:application/octet-stream;base64,"
                                                         "AAAAAAEAAAACAAAAAAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}});
  doc["accessors"][0] = {{"componentType", 5126}, {"count", 3 * triangles}, {"type", "VEC3"},
                         {"sparse", {{"count", 3}, {"indices", {{"bufferView", 0}, {"componentType", 5125}}},
                                     {"values", {{"bufferView", 1}}}}}};
  doc["bufferViews"] = Json::array({Json{{"buffer", 0}, {"byteLength", 12}},
                                    Json{{"buffer", 0}, {"byteOffset", 12}, {"byteLength", 36}}});
  doc["nodes"] = Json::array({Json{{"children", Json::array()}}});
  for (int i = 1; i <= nodes; ++i) {
    doc["nodes"].push_back({{"mesh", 0}, {"translation", {0.0, 0.0, -0.01 * i}}});
    doc["nodes"][0]["children"].push_back(i);
  }
  return doc;
}

}  // namespace

TEST_CASE("inputs: instancing beyond the memory budget is refused before the triangles are made, with the numbers",
          "[loader][reliability]") {
  const fs::path dir = folder("instancing");
  const std::string path = save(dir / "copies.gltf", instanced_scene(1000, 1000));  // 10^6 triangles
  MemoryBudget budget(100u << 20);                                                 // 100 MiB
  require_bad_scene(path, {"its nodes place 1000000 triangles", "need 0.2 GB of memory at 192 bytes each",
                           "this machine has 0.1 GB available"});
  pt::set_scene_memory_budget(1u << 30);
  pt::Scene scene = pt::load_gltf(path);
  CHECK(scene.triangles.size() == 1000);  // one of each copy has an area
}

TEST_CASE("inputs: instancing beyond what the BVH takes is refused before the triangles are made",
          "[loader][reliability]") {
  const fs::path dir = folder("bvh_limit");
  // 300 copies of 10^6 triangles: 3 x 10^8, above the BVH's 2^28, from a file of 20 KB.
  require_bad_scene(save(dir / "copies.gltf", instanced_scene(300, 1000000)),
                    {"its nodes place 300000000 triangles", "more than the 268435456 the BVH takes"});
}

}  // namespace test_scene_inputs
