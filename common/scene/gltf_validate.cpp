// Checks of a glTF 2.0 file that tinygltf leaves to its user, for the loader of
// the contract (README.md) "Scenes": the container and JSON before tinygltf reads them, references
// and the node tree after, and every accessor a triangle reads (offsets near 2^64
// included: all sizes are added and multiplied with overflow checks).
#include "common/scene/gltf_validate.h"

#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>

#include <nlohmann/json.hpp>

#include "common/base/error.h"

namespace pt::gltf {

namespace {

using Json = nlohmann::json;
namespace fs = std::filesystem;

constexpr int kMaxJsonDepth = 64;  // real files nest about 8 levels
const std::set<std::string> kSizeKeys = {"byteOffset", "byteLength", "byteStride", "count"};
const std::set<std::string> kSupportedExtensions = {"KHR_materials_emissive_strength",
                                                    "KHR_materials_transmission", "KHR_materials_ior",
                                                    "KHR_lights_punctual"};

std::string str(std::uint64_t n) { return std::to_string(n); }

// "needs N bytes, has M", or the overflow that prevents saying N.
std::string need_text(bool overflowed, std::uint64_t needed, std::uint64_t has) {
  if (overflowed) return "its offsets overflow 64 bits, has " + str(has) + " bytes";
  return "needs " + str(needed) + " bytes, has " + str(has);
}

std::uint32_t read_u32_le(const unsigned char* p) {
  return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 |
         std::uint32_t(p[3]) << 24;
}

std::vector<unsigned char> read_file(const std::string& path) {
  std::error_code ec;
  fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) {
    throw Error(kExitBadScene,
                "cannot open scene '" + path + "': no such file; check the path or use builtin:cornell");
  }
  if (fs::is_directory(status)) {
    throw Error(kExitBadScene, "cannot open scene '" + path + "': it is a folder; give a .gltf or .glb file");
  }
  if (fs::file_size(path, ec) > UINT_MAX && !ec) {
    throw Error(kExitBadScene,
                "cannot read scene '" + path + "': larger than 4 GiB, which tinygltf cannot read");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw Error(kExitBadScene,
                "cannot open scene '" + path + "': " + std::strerror(errno) + "; check its permissions");
  }
  return std::vector<unsigned char>(std::istreambuf_iterator<char>(in), {});
}

// The JSON chunk of a .glb, after checking the container (12-byte header, then chunks of
// 8-byte header + data) with the arithmetic that tinygltf 2.7 gets slightly wrong.
std::string glb_json(std::vector<unsigned char>& bytes, const std::string& file) {
  const std::string bad = "not a valid .glb: ";
  if (bytes.size() < 20 || std::memcmp(bytes.data(), "glTF", 4) != 0) {
    fail(file, bad + "no glTF header; check that it is a binary glTF file");
  }
  std::uint32_t version = read_u32_le(&bytes[4]), length = read_u32_le(&bytes[8]);
  if (version != 2) fail(file, bad + "version " + str(version) + "; only glTF 2.0 is supported");
  if (length > bytes.size() || length < 20) {
    fail(file,
         bad + "header says " + str(length) + " bytes, file has " + str(bytes.size()) + ": " + kReexport);
  }
  bytes.resize(length);
  std::uint64_t json_length = read_u32_le(&bytes[12]);
  std::uint64_t json_end = 20 + json_length;
  if (read_u32_le(&bytes[16]) != 0x4E4F534Au || json_length == 0 || json_end > length) {
    fail(file, bad + "the JSON chunk is missing or runs past the end: " + kReexport);
  }
  if (json_length % 4 != 0) fail(file, bad + "the JSON chunk is not padded to 4 bytes: " + kReexport);
  if (json_end < length) {  // a BIN chunk follows
    if (json_end + 8 > length || json_end + 8 + read_u32_le(&bytes[json_end]) > length) {
      fail(file, bad + "the BIN chunk runs past the end of the file: " + kReexport);
    }
  }
  return std::string(bytes.begin() + 20, bytes.begin() + std::ptrdiff_t(json_end));
}

// Integers that tinygltf would silently truncate or drop: sizes must be unsigned, every
// other integer must fit an int. Also bounds the nesting (tinygltf recurses into it).
void check_numbers(const Json& j, const std::string& where, int depth, bool in_extras,
                   const std::string& file) {
  if (depth > kMaxJsonDepth) fail(file, where + " is nested too deeply: " + kReexport);
  if (j.is_object() || j.is_array()) {
    std::size_t i = 0;
    for (auto it = j.begin(); it != j.end(); ++it, ++i) {
      bool object = j.is_object();
      std::string w =
          object ? (where.empty() ? it.key() : where + "." + it.key()) : where + "[" + str(i) + "]";
      bool extras = in_extras || (object && it.key() == "extras");
      if (object && !extras && kSizeKeys.count(it.key())) {
        if (!it->is_number_unsigned()) {
          fail(file,
               w + " must be a non-negative integer, is " + it->dump().substr(0, 40) + ": " + kReexport);
        }
        continue;
      }
      check_numbers(*it, w, depth + 1, extras, file);
    }
  } else if (j.is_number_integer() && !in_extras) {
    bool fits = j.is_number_unsigned() ? j.get<std::uint64_t>() <= std::uint64_t(INT_MAX)
                                       : j.get<std::int64_t>() >= INT_MIN && j.get<std::int64_t>() <= INT_MAX;
    if (!fits) fail(file, where + " = " + j.dump() + " is out of range: " + kReexport);
  }
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return 0;  // as tinygltf reads a bad digit
}

// Percent-decoding as tinygltf does it before opening a URI ('+' is a space there too).
std::string decode_uri(const std::string& uri) {
  std::string out;
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '+') {
      out += ' ';
    } else if (uri[i] == '%' && i + 2 < uri.size()) {
      out += char(hex_digit(uri[i + 1]) * 16 + hex_digit(uri[i + 2]));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

bool leaves_folder(const std::string& path) {
  if (path.empty()) return false;
  if (path[0] == '/' || path[0] == '\\') return true;                                          // absolute
  if (path.size() > 1 && std::isalpha((unsigned char)path[0]) && path[1] == ':') return true;  // C:
  std::size_t start = 0;
  while (start <= path.size()) {
    std::size_t end = path.find_first_of("/\\", start);
    if (end == std::string::npos) end = path.size();
    if (path.compare(start, end - start, "..") == 0 && end - start == 2) return true;
    start = end + 1;
  }
  return false;
}

// Buffer and image URIs stay inside the scene's folder; external buffers must exist.
void check_uris(const Json& doc, const std::string& base_dir, const std::string& file) {
  for (const char* array : {"buffers", "images"}) {
    auto items = doc.find(array);
    if (items == doc.end() || !items->is_array()) continue;
    for (std::size_t i = 0; i < items->size(); ++i) {
      const Json& item = (*items)[i];
      if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string()) continue;
      std::string uri = item["uri"].get<std::string>();
      std::string where = std::string(array) + "[" + str(i) + "].uri";
      if (tinygltf::IsDataURI(uri)) continue;
      std::string decoded = decode_uri(uri);
      if (leaves_folder(uri) || leaves_folder(decoded)) {
        fail(file, where + " '" + uri.substr(0, 80) +
                       "' points outside the scene's folder: keep buffers and images next to "
                       "the .gltf (or embed them) and re-export");
      }
      std::error_code ec;
      if (std::string(array) == "buffers" && !fs::is_regular_file(fs::path(base_dir) / decoded, ec)) {
        fail(file, where + " '" + uri.substr(0, 80) +
                       "' was not found next to the scene: copy it there or re-export as .glb");
      }
    }
  }
}

const Json* element(const Json& doc, const char* array, const Json& index) {
  auto items = doc.find(array);
  if (items == doc.end() || !items->is_array() || !index.is_number_integer()) return nullptr;
  std::int64_t i = index.get<std::int64_t>();
  if (i < 0 || std::uint64_t(i) >= items->size() || !(*items)[std::size_t(i)].is_object()) return nullptr;
  return &(*items)[std::size_t(i)];
}

// tinygltf hands &buffer.data[view.byteOffset] to the image loader unchecked: check the
// bufferViews of images against the buffers' stated lengths before it runs.
void check_image_views(const Json& doc, const std::string& file) {
  auto images = doc.find("images");
  if (images == doc.end() || !images->is_array()) return;
  for (std::size_t i = 0; i < images->size(); ++i) {
    const Json& image = (*images)[i];
    if (!image.is_object() || !image.contains("bufferView")) continue;
    std::string where = "images[" + str(i) + "]";
    const Json* view = element(doc, "bufferViews", image["bufferView"]);
    if (!view) fail(file, where + ".bufferView is out of range: " + std::string(kReexport));
    const Json* buffer = view->contains("buffer") ? element(doc, "buffers", (*view)["buffer"]) : nullptr;
    if (!buffer) fail(file, where + ": its bufferView's buffer is out of range: " + std::string(kReexport));
    if (!view->contains("byteLength") || !buffer->contains("byteLength")) continue;  // tinygltf says
    std::uint64_t offset = view->value("byteOffset", std::uint64_t(0));
    std::uint64_t length = (*view)["byteLength"].get<std::uint64_t>();
    std::uint64_t has = (*buffer)["byteLength"].get<std::uint64_t>(), end = 0;
    bool overflow = __builtin_add_overflow(offset, length, &end);
    if (overflow || end > has || offset >= has) {  // tinygltf takes &data[offset] even for length 0
      fail(file, where + ": bufferViews[" + image["bufferView"].dump() + "] runs past buffers[" +
                     (*view)["buffer"].dump() + "] (" + need_text(overflow, end, has) + "): " + kReexport);
    }
  }
}

void check_index(const std::string& file, int index, std::size_t size, const std::string& where,
                 const char* array) {
  if (index < 0 || std::size_t(index) >= size) {
    fail(file, where + " = " + std::to_string(index) + " is out of range (" + array + " has " + str(size) +
                   (size == 1 ? " entry): " : " entries): ") + kReexport);
  }
}

void check_extensions(const tinygltf::Model& model, const std::string& file) {
  for (const std::string& name : model.extensionsRequired) {
    if (!kSupportedExtensions.count(name)) {
      fail(file, "extensionsRequired lists " + name +
                     ", which this renderer does not support: re-export without it (supported: "
                     "KHR_materials_emissive_strength, KHR_materials_transmission, "
                     "KHR_materials_ior, KHR_lights_punctual)");
    }
  }
  std::string ignored;
  for (const std::string& name : model.extensionsUsed) {
    if (!kSupportedExtensions.count(name)) ignored += (ignored.empty() ? "" : ", ") + name;
  }
  if (!ignored.empty()) warn_once(file + ": scene uses extensions " + ignored + "; they are not modelled");
}

void check_node(const tinygltf::Model& model, std::size_t i, const std::string& file) {
  const tinygltf::Node& node = model.nodes[i];
  std::string where = "nodes[" + str(i) + "]";
  if (node.mesh != -1) check_index(file, node.mesh, model.meshes.size(), where + ".mesh", "meshes");
  if (node.camera != -1) check_index(file, node.camera, model.cameras.size(), where + ".camera", "cameras");
  if (node.skin != -1) check_index(file, node.skin, model.skins.size(), where + ".skin", "skins");
  for (std::size_t k = 0; k < node.children.size(); ++k) {
    check_index(file, node.children[k], model.nodes.size(), where + ".children[" + str(k) + "]", "nodes");
  }
  auto light = node.extensions.find("KHR_lights_punctual");
  if (light != node.extensions.end()) {
    std::string w = where + ".extensions.KHR_lights_punctual.light";
    if (!light->second.Has("light") || !light->second.Get("light").IsInt()) {
      fail(file, w + " is missing or not an integer: " + std::string(kReexport));
    }
    check_index(file, light->second.Get("light").GetNumberAsInt(), model.lights.size(), w, "lights");
  }
  // Transforms: a full matrix, or translation / rotation / scale of the right lengths
  const std::pair<const std::vector<double>*, std::pair<const char*, std::size_t>> parts[] = {
      {&node.matrix, {"matrix", 16}},
      {&node.translation, {"translation", 3}},
      {&node.rotation, {"rotation", 4}},
      {&node.scale, {"scale", 3}}};
  for (const auto& [values, name_size] : parts) {
    std::string w = where + "." + name_size.first;
    if (!values->empty() && values->size() != name_size.second) {
      fail(file,
           w + " has " + str(values->size()) + " numbers, needs " + str(name_size.second) + ": " + kReexport);
    }
    for (std::size_t k = 0; k < values->size(); ++k)
      checked_float(file, (*values)[k], w + "[" + str(k) + "]");
  }
  double q2 = 0.0;
  for (double q : node.rotation) q2 += q * q;
  if (!node.rotation.empty() && !(q2 > 1e-12))
    fail(file, where + ".rotation is a zero quaternion: " + std::string(kReexport));
}

// One parent per node and no cycles; scenes list roots, each once.
std::vector<int> check_tree(const tinygltf::Model& model, const std::string& file) {
  std::size_t n = model.nodes.size();
  std::vector<int> parent(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    for (int c : model.nodes[i].children) {
      std::string child = "nodes[" + std::to_string(c) + "]", self = "nodes[" + str(i) + "]";
      if (std::size_t(c) == i)
        fail(file, self + " is its own child: the node tree has a cycle; " + kReexport);
      if (parent[c] == int(i)) fail(file, child + " is listed twice in " + self + ".children: " + kReexport);
      if (parent[c] != -1) {
        fail(file, child + " is a child of both nodes[" + std::to_string(parent[c]) + "] and " + self +
                       ": glTF nodes form trees; " + kReexport);
      }
      parent[c] = int(i);
    }
  }
  std::vector<char> state(n, 0);  // 0 unseen, 1 on the chain being followed, 2 known acyclic
  for (std::size_t i = 0; i < n; ++i) {
    int j = int(i);
    while (j != -1 && state[j] == 0) state[j] = 1, j = parent[j];
    if (j != -1 && state[j] == 1) {
      fail(file,
           "nodes[" + std::to_string(j) + "] is its own ancestor: the node tree has a cycle; " + kReexport);
    }
    for (j = int(i); j != -1 && state[j] == 1; j = parent[j]) state[j] = 2;
  }
  for (std::size_t s = 0; s < model.scenes.size(); ++s) {
    std::set<int> listed;
    for (std::size_t k = 0; k < model.scenes[s].nodes.size(); ++k) {
      int r = model.scenes[s].nodes[k];
      std::string where = "scenes[" + str(s) + "].nodes[" + str(k) + "]";
      check_index(file, r, n, where, "nodes");
      if (parent[r] != -1) {
        fail(file, where + " = " + std::to_string(r) + " is a child of nodes[" + std::to_string(parent[r]) +
                       "]; a scene lists root nodes only: " + kReexport);
      }
      if (!listed.insert(r).second)
        fail(file, where + " lists nodes[" + std::to_string(r) + "] twice: " + kReexport);
    }
  }
  return parent;
}

struct AccessorData {
  const unsigned char* first;  // the first element
  std::size_t stride;          // bytes from one element to the next
  std::size_t count;
};

// Checks an accessor against its bufferView and the bufferView against its buffer.
AccessorData locate(const tinygltf::Model& model, int index, std::size_t element_size,
                    const std::string& file, const std::string& what) {
  check_index(file, index, model.accessors.size(), what, "accessors");
  const tinygltf::Accessor& a = model.accessors[index];
  if (a.sparse.isSparse)
    fail(file, what + " is sparse; sparse accessors are not supported: re-export without them");
  if (a.count == 0) fail(file, what + " has count 0; a primitive needs vertices: " + std::string(kReexport));
  if (a.bufferView < 0) fail(file, what + " has no bufferView (no data): " + std::string(kReexport));
  check_index(file, a.bufferView, model.bufferViews.size(), what + ".bufferView", "bufferViews");
  const tinygltf::BufferView& v = model.bufferViews[a.bufferView];
  std::string view = "bufferViews[" + std::to_string(a.bufferView) + "]";
  check_index(file, v.buffer, model.buffers.size(), view + ".buffer", "buffers");
  std::uint64_t view_end = 0, has = model.buffers[v.buffer].data.size();
  bool overflow = __builtin_add_overflow(std::uint64_t(v.byteOffset), std::uint64_t(v.byteLength), &view_end);
  if (overflow || view_end > has) {
    fail(file, view + " (used by " + what + ") runs past buffers[" + std::to_string(v.buffer) + "] (" +
                   need_text(overflow, view_end, has) + "): " + kReexport);
  }
  std::size_t stride = v.byteStride != 0 ? v.byteStride : element_size;
  if (stride < element_size) {
    fail(file, view + ".byteStride " + str(stride) + " is smaller than an element of " + what + " (" +
                   str(element_size) + " bytes): " + kReexport);
  }
  std::uint64_t needed = 0;  // byteOffset + stride * (count - 1) + element size
  overflow = __builtin_mul_overflow(std::uint64_t(stride), std::uint64_t(a.count - 1), &needed) ||
             __builtin_add_overflow(needed, std::uint64_t(a.byteOffset), &needed) ||
             __builtin_add_overflow(needed, std::uint64_t(element_size), &needed);
  if (overflow || needed > v.byteLength) {
    fail(file,
         what + " runs past " + view + " (" + need_text(overflow, needed, v.byteLength) + "): " + kReexport);
  }
  return {model.buffers[v.buffer].data.data() + v.byteOffset + a.byteOffset, stride, a.count};
}

}  // namespace

void fail(const std::string& file, const std::string& message) {
  std::string line = file + ": " + message;
  for (char& c : line) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  throw Error(kExitBadScene, line);
}

float checked_float(const std::string& file, double value, const std::string& where, double lo, double hi) {
  float f = float(value);
  if (!std::isfinite(f)) fail(file, where + " is not a finite 32-bit float: " + std::string(kReexport));
  if (!(value >= lo && value <= hi)) {
    char range[64];
    std::snprintf(range, sizeof range, "[%g, %g]", lo, hi);
    fail(file, where + " = " + std::to_string(value) + " is outside " + range + ": " + kReexport);
  }
  return f;
}

SourceFile read_and_precheck(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower((unsigned char)c));
  if (ext != ".gltf" && ext != ".glb") {
    throw Error(kExitBadScene, "cannot read scene '" + path +
                                   "': not a .gltf or .glb file; give a glTF 2.0 "
                                   "file or builtin:NAME");
  }
  SourceFile source;
  source.binary = ext == ".glb";
  source.bytes = read_file(path);
  source.base_dir = fs::path(path).parent_path().string();
  std::string text =
      source.binary ? glb_json(source.bytes, path) : std::string(source.bytes.begin(), source.bytes.end());
  Json doc;
  try {
    doc = Json::parse(text);
  } catch (const Json::exception& e) {
    std::string what = e.what();  // may quote raw bytes of the file: keep printable ASCII
    for (char& c : what) c = (c >= ' ' && c <= '~') ? c : '?';
    fail(path, "invalid JSON (" + what + "): the file is damaged or not glTF; re-export it");
  }
  if (!doc.is_object()) fail(path, "invalid JSON for glTF: the top level is not an object; re-export it");
  check_numbers(doc, "", 0, false, path);
  check_uris(doc, source.base_dir, path);
  check_image_views(doc, path);
  return source;
}

std::vector<int> check_model(const tinygltf::Model& model, const std::string& file) {
  check_extensions(model, file);
  if (model.defaultScene != -1) check_index(file, model.defaultScene, model.scenes.size(), "scene", "scenes");
  for (std::size_t i = 0; i < model.nodes.size(); ++i) check_node(model, i, file);
  for (std::size_t m = 0; m < model.meshes.size(); ++m) {
    for (std::size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
      const tinygltf::Primitive& prim = model.meshes[m].primitives[p];
      std::string where = "meshes[" + str(m) + "].primitives[" + str(p) + "]";
      if (prim.material != -1)
        check_index(file, prim.material, model.materials.size(), where + ".material", "materials");
      if (prim.indices != -1)
        check_index(file, prim.indices, model.accessors.size(), where + ".indices", "accessors");
      for (const auto& [name, accessor] : prim.attributes) {
        check_index(file, accessor, model.accessors.size(), where + ".attributes." + name, "accessors");
      }
    }
  }
  return check_tree(model, file);
}

std::vector<glm::vec3> read_positions(const tinygltf::Model& model, int accessor, const std::string& file,
                                      const std::string& what) {
  check_index(file, accessor, model.accessors.size(), what, "accessors");
  const tinygltf::Accessor& a = model.accessors[accessor];
  if (a.type != TINYGLTF_TYPE_VEC3 || a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
    fail(file, what + " must be VEC3 of FLOAT (type " + std::to_string(a.type) + ", componentType " +
                   std::to_string(a.componentType) + "): re-export without mesh quantization");
  }
  AccessorData data = locate(model, accessor, 12, file, what);
  std::vector<glm::vec3> positions(data.count);
  for (std::size_t i = 0; i < data.count; ++i) {
    std::memcpy(&positions[i], data.first + i * data.stride, 12);
    const glm::vec3& p = positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      fail(file, what + " vertex " + str(i) + " is not finite (" + std::to_string(p.x) + ", " +
                     std::to_string(p.y) + ", " + std::to_string(p.z) + "): " + kReexport);
    }
  }
  return positions;
}

std::vector<std::uint32_t> read_indices(const tinygltf::Model& model, int accessor, std::size_t vertex_count,
                                        const std::string& file, const std::string& what) {
  check_index(file, accessor, model.accessors.size(), what, "accessors");
  const tinygltf::Accessor& a = model.accessors[accessor];
  std::size_t size = a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 1
                     : a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                     : a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT   ? 4
                                                                                 : 0;
  if (a.type != TINYGLTF_TYPE_SCALAR || size == 0) {
    fail(file, what + " must be SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT: " +
                   std::string(kReexport));
  }
  AccessorData data = locate(model, accessor, size, file, what);
  std::vector<std::uint32_t> indices(data.count);
  for (std::size_t i = 0; i < data.count; ++i) {
    const unsigned char* p = data.first + i * data.stride;
    std::uint32_t index = size == 1 ? p[0] : size == 2 ? std::uint32_t(p[0] | p[1] << 8) : read_u32_le(p);
    if (index >= vertex_count) {
      fail(file, what + " entry " + str(i) + " is " + str(index) + ", past the vertex count (" +
                     str(vertex_count) + "): " + kReexport);
    }
    indices[i] = index;
  }
  return indices;
}

}  // namespace pt::gltf
