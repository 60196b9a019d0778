// A small glTF 2.0 writer for tests that make their scene in the test itself (cameras,
// punctual lights): meshes from lists of points, nodes, materials, cameras and
// KHR_lights_punctual lights, written as one .gltf with its buffer embedded (base64).
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

class GltfWriter {
 public:
  using Json = nlohmann::json;

  GltfWriter() {
    doc_ = {{"asset", {{"version", "2.0"}, {"generator", "tests/support/gltf_writer.h"}}},
            {"scene", 0},
            {"scenes", Json::array({Json{{"nodes", Json::array()}}})}};
  }

  // A mesh of triangles (3 points each, counter-clockwise seen from the front), no indices.
  int mesh(const std::vector<glm::vec3>& points, int material = -1) {
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (glm::vec3 p : points) lo = glm::min(lo, p), hi = glm::max(hi, p);
    std::size_t offset = bin_.size();
    bin_.resize(offset + points.size() * 12);
    std::memcpy(bin_.data() + offset, points.data(), points.size() * 12);
    int view = add("bufferViews", {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", points.size() * 12}});
    int accessor = add("accessors", {{"bufferView", view},
                                     {"componentType", 5126},
                                     {"count", points.size()},
                                     {"type", "VEC3"},
                                     {"min", {lo.x, lo.y, lo.z}},
                                     {"max", {hi.x, hi.y, hi.z}}});
    Json primitive = {{"attributes", {{"POSITION", accessor}}}};
    if (material >= 0) primitive["material"] = material;
    return add("meshes", {{"primitives", Json::array({primitive})}});
  }

  // A mesh of triangles as mesh() with further vertex attributes, each a list of floats with
  // `components` per vertex: {"NORMAL", 3, normals}, {"TEXCOORD_0", 2, uv}, {"TANGENT", 4, t}.
  struct Attribute {
    std::string name;
    int components;
    std::vector<float> values;
  };
  int mesh_with(const std::vector<glm::vec3>& points, const std::vector<Attribute>& attributes, int material = -1) {
    int m = mesh(points, material);
    Json& primitive = doc_["meshes"][m]["primitives"][0];
    for (const Attribute& a : attributes) {
      static const char* kTypes[] = {"", "SCALAR", "VEC2", "VEC3", "VEC4"};
      std::size_t offset = bin_.size(), bytes = a.values.size() * 4;
      bin_.resize(offset + bytes);
      std::memcpy(bin_.data() + offset, a.values.data(), bytes);
      int view = add("bufferViews", {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}});
      primitive["attributes"][a.name] = add("accessors", {{"bufferView", view},
                                                          {"componentType", 5126},
                                                          {"count", a.values.size() / std::size_t(a.components)},
                                                          {"type", kTypes[a.components]}});
    }
    return m;
  }

  // A texture of the image at `uri` (relative to the file), default sampler.
  int texture(const std::string& uri) {
    int image = add("images", {{"uri", uri}});
    return add("textures", {{"source", image}});
  }

  // A quad p0 p1 p2 p3 (counter-clockwise seen from its front) as two triangles.
  int quad(glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, glm::vec3 p3, int material = -1) {
    return mesh({p0, p1, p2, p0, p2, p3}, material);
  }

  // A Lambertian material: metallic 0 and no specular layer (KHR_materials_specular's
  // specularFactor 0), so that the glTF material is the base alone.
  int diffuse(glm::vec3 albedo) {
    return material({{"pbrMetallicRoughness",
                      {{"baseColorFactor", {albedo.x, albedo.y, albedo.z, 1.0}}, {"metallicFactor", 0.0}}},
                     {"extensions", {{"KHR_materials_specular", {{"specularFactor", 0.0}}}}}});
  }

  // A glTF material as written: {"pbrMetallicRoughness": {...}, "extensions": {...}}.
  int material(Json fields) { return add("materials", std::move(fields)); }

  // Names an extension in extensionsUsed (the loader warns about those it does not model).
  void uses(const std::string& extension) {
    if (!doc_.contains("extensionsUsed")) doc_["extensionsUsed"] = Json::array();
    doc_["extensionsUsed"].push_back(extension);
  }

  int perspective(double yfov, double aspect_ratio = 0.0, const std::string& name = "") {
    Json p = {{"yfov", yfov}, {"znear", 0.01}};
    if (aspect_ratio > 0.0) p["aspectRatio"] = aspect_ratio;
    Json c = {{"type", "perspective"}, {"perspective", p}};
    if (!name.empty()) c["name"] = name;
    return add("cameras", c);
  }

  // A KHR_lights_punctual light: type "point", "spot" or "directional".
  int light(const std::string& type, glm::vec3 color, double intensity, double inner = -1.0, double outer = -1.0) {
    Json l = {{"type", type}, {"color", {color.x, color.y, color.z}}, {"intensity", intensity}};
    if (type == "spot") {
      l["spot"] = Json::object();
      if (inner >= 0.0) l["spot"]["innerConeAngle"] = inner;
      if (outer >= 0.0) l["spot"]["outerConeAngle"] = outer;
    }
    Json& ext = doc_["extensions"]["KHR_lights_punctual"]["lights"];
    if (ext.is_null()) ext = Json::array();
    ext.push_back(l);
    if (!doc_.contains("extensionsUsed")) doc_["extensionsUsed"] = Json::array({"KHR_lights_punctual"});
    return int(ext.size()) - 1;
  }

  // A root node; `fields` as glTF spells them (mesh, camera, translation, rotation, name...).
  int node(Json fields) {
    int index = add("nodes", std::move(fields));
    doc_["scenes"][0]["nodes"].push_back(index);
    return index;
  }
  int light_node(int light, Json fields = Json::object()) {
    fields["extensions"]["KHR_lights_punctual"]["light"] = light;
    return node(std::move(fields));
  }

  // For tests that need more than the helpers above (tests/support/gltf_textured.h): an
  // item appended to a top-level array, and bytes appended to the buffer as a bufferView
  // (4-byte aligned on both ends, so that accessors after it stay aligned); their indices.
  int item(const char* array, Json fields) { return add(array, std::move(fields)); }
  int view(const void* bytes, std::size_t size) {
    bin_.resize((bin_.size() + 3) / 4 * 4);
    std::size_t offset = bin_.size();
    bin_.resize(offset + size);
    std::memcpy(bin_.data() + offset, bytes, size);
    int index = add("bufferViews", {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", size}});
    bin_.resize((bin_.size() + 3) / 4 * 4);
    return index;
  }

  // Writes the document to `path` (its folder is made) and returns the path.
  std::string write(const std::string& path) {
    Json doc = doc_;
    if (!bin_.empty()) doc["buffers"] = Json::array({Json{{"byteLength", bin_.size()}, {"uri", data_uri()}}});
    std::filesystem::create_directories(std::filesystem::path(path).parent_path());
    std::ofstream(path) << doc.dump(1) << "\n";
    return path;
  }

 private:
  int add(const char* array, Json item) {
    Json& a = doc_[array];
    if (a.is_null()) a = Json::array();
    a.push_back(std::move(item));
    return int(a.size()) - 1;
  }

  std::string data_uri() const {
    static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out = "data:application/octet-stream;base64,";
    for (std::size_t i = 0; i < bin_.size(); i += 3) {
      std::uint32_t v = std::uint32_t(bin_[i]) << 16;
      if (i + 1 < bin_.size()) v |= std::uint32_t(bin_[i + 1]) << 8;
      if (i + 2 < bin_.size()) v |= bin_[i + 2];
      out += k[(v >> 18) & 63];
      out += k[(v >> 12) & 63];
      out += i + 1 < bin_.size() ? k[(v >> 6) & 63] : '=';
      out += i + 2 < bin_.size() ? k[v & 63] : '=';
    }
    return out;
  }

  Json doc_;
  std::vector<unsigned char> bin_;
};

}  // namespace pt::test
