// Test support for what a glTF file draws (test_gltf_draws.cpp, tests/stages/test_cli_draws.cpp):
// small glTF 2.0 documents built in the test, with primitives of any mode, indices, several
// scenes and EXT_mesh_gpu_instancing, written as a .gltf with its buffer in a .bin beside it.
// Not part of the article: test machinery.
#pragma once

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

namespace pt::test {

class DrawFile {
 public:
  using Json = nlohmann::json;

  DrawFile() { doc = {{"asset", {{"version", "2.0"}}}}; }

  // An accessor over `count` elements of `type` ("VEC3", "SCALAR"...) copied from `data`.
  int accessor(const void* data, std::size_t bytes, int component_type, std::size_t count, const std::string& type) {
    std::size_t offset = bin_.size();
    bin_.resize(offset + (bytes + 3) / 4 * 4);
    std::memcpy(bin_.data() + offset, data, bytes);
    int view = add("bufferViews", {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}});
    return add("accessors", {{"bufferView", view}, {"componentType", component_type}, {"count", count}, {"type", type}});
  }
  int vec3s(const std::vector<glm::vec3>& v) { return accessor(v.data(), v.size() * 12, 5126, v.size(), "VEC3"); }
  int vec4s(const std::vector<glm::vec4>& v) { return accessor(v.data(), v.size() * 16, 5126, v.size(), "VEC4"); }
  int u16s(const std::vector<std::uint16_t>& v) { return accessor(v.data(), v.size() * 2, 5123, v.size(), "SCALAR"); }

  // A mesh of one primitive of `mode` over `points` (indices: -1 for none, else an accessor).
  int mesh(const std::vector<glm::vec3>& points, int mode, int indices = -1) {
    Json prim = {{"attributes", {{"POSITION", vec3s(points)}}}, {"mode", mode}};
    if (indices >= 0) prim["indices"] = indices;
    return add("meshes", {{"primitives", Json::array({prim})}});
  }

  int node(Json fields) { return add("nodes", std::move(fields)); }

  // A scene of root nodes; the first scene added is the file's `scene` unless set otherwise.
  int scene(const std::vector<int>& nodes, const std::string& name = "") {
    Json s = {{"nodes", nodes}};
    if (!name.empty()) s["name"] = name;
    int index = add("scenes", s);
    if (!doc.contains("scene")) doc["scene"] = index;
    return index;
  }

  // Writes NAME.gltf and NAME.bin into `dir`; returns the .gltf's path.
  std::string write(const std::filesystem::path& dir, const std::string& name) {
    std::filesystem::create_directories(dir);
    Json d = doc;
    if (!bin_.empty()) {
      d["buffers"] = Json::array({Json{{"byteLength", bin_.size()}, {"uri", name + ".bin"}}});
      std::ofstream(dir / (name + ".bin"), std::ios::binary)
          .write(reinterpret_cast<const char*>(bin_.data()), std::streamsize(bin_.size()));
    }
    std::ofstream(dir / (name + ".gltf")) << d.dump(1) << "\n";
    return (dir / (name + ".gltf")).string();
  }

  Json doc;

 private:
  int add(const char* array, Json item) {
    Json& a = doc[array];
    if (a.is_null()) a = Json::array();
    a.push_back(std::move(item));
    return int(a.size()) - 1;
  }

  std::vector<unsigned char> bin_;
};

}  // namespace pt::test
