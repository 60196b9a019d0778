// The checks of a glTF 2.0 file before tinygltf reads it, for the loader of the contract
// (README.md) "Scenes": the file itself (a regular file of at most 1 GiB, refused before it is
// read; a Git LFS pointer is named as one), the GLB container, the JSON's nesting (in the text,
// before any parser) and integers, extensionsRequired (before tinygltf reads buffers an
// extension may have compressed), and the sizes tinygltf reads into an int; then buffer and
// image URIs and the bufferViews of images (gltf_precheck_uris.cpp).
#include <cctype>
#include <climits>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>

#include <nlohmann/json.hpp>

#include "common/base/error.h"
#include "common/scene/gltf_precheck_uris.h"
#include "common/scene/gltf_validate.h"
#include "common/scene/gltf_validate_detail.h"

namespace pt::gltf {

using namespace detail;

namespace {

using Json = nlohmann::json;
namespace fs = std::filesystem;

constexpr int kMaxJsonDepth = 64;  // real files nest about 8 levels
// Where the bytes themselves are damaged, a fresh copy or export helps (unlike kReexport's
// violations of the specification, which the same exporter would write again).
const std::string kDamaged = "the file is truncated or damaged; copy or export it again";
const std::set<std::string> kSizeKeys = {"byteOffset", "byteLength", "byteStride", "count"};

// The extensions that change what buffers or images hold, and the way out of each.
const std::map<std::string, std::string> kUnreadExtensions = {
    {"KHR_draco_mesh_compression",
     "(Draco-compressed meshes), which this renderer does not read: re-export without compression "
     "(Blender: uncheck Compression in the glTF exporter) or decompress it with "
     "`gltf-transform copy IN OUT`"},
    {"EXT_meshopt_compression",
     "(meshoptimizer-compressed buffers), which this renderer does not read: re-export without "
     "compression or decompress it with `gltfpack -noq -i IN -o OUT` (gltfpack 0.21 or later)"},
    {"KHR_mesh_quantization",
     "(vertex attributes stored as 8- or 16-bit integers), which this renderer does not read: "
     "re-export without quantization or dequantize it with `gltf-transform dequantize IN OUT`"},
    {"KHR_texture_basisu",
     "(KTX2 / Basis Universal textures), which this renderer does not read: re-export with PNG or "
     "JPEG textures"},
    {"EXT_texture_webp",
     "(WebP textures), which this renderer does not read: re-export with PNG or JPEG textures "
     "(Blender: Images Automatic or JPEG in the glTF exporter)"},
};

// Checked before anything else in the JSON: a compressed file's accessors may have no
// data at all, and tinygltf would only call it malformed.
void check_required_extensions(const Json& doc, const std::string& file) {
  auto required = doc.find("extensionsRequired");
  if (required == doc.end() || !required->is_array()) return;  // tinygltf says
  for (const Json& entry : *required) {
    if (!entry.is_string()) continue;
    std::string name = entry.get<std::string>();
    if (kSupportedExtensions.count(name)) continue;
    auto known = kUnreadExtensions.find(name);
    if (known != kUnreadExtensions.end())
      fail(file, "extensionsRequired lists " + name + " " + known->second);
    fail(file, "extensionsRequired lists " + name.substr(0, 80) +
                   ", which this renderer does not support: re-export without it (supported: " +
                   supported_extensions_text() + ")");
  }
}

// The scene file, refused before it is read when it is not a regular file (a FIFO would be
// read without end, a device or a sparse file of gigabytes would be read whole) or is larger
// than kMaxSceneFileBytes.
std::vector<unsigned char> read_file(const std::string& path) {
  return read_regular_file(path, [&](const std::string& why) {
    std::string advice = "give a .gltf or .glb file";
    if (why == "no such file") advice = "check the path or use builtin:cornell";
    if (why.find("more than") != std::string::npos) advice = "simplify the scene (fewer or coarser meshes)";
    if (why.find("permissions") != std::string::npos) advice.clear();
    throw Error(kExitBadScene, "cannot read scene '" + path + "': " + why + (advice.empty() ? "" : "; " + advice));
  });
}

// The deepest nesting of arrays and objects in JSON text, counted outside strings before any
// parser sees the text: a value nested 100,000 deep is 200 KB, and code that walks a parsed
// value by recursion (dump(), tinygltf's extras) overflows the stack on it.
void check_nesting(const std::string& text, const std::string& file) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') ++i;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth) {
        fail(file, "its JSON nests arrays and objects deeper than " + str(kMaxJsonDepth) + " levels (at byte " +
                       str(i) + "); glTF files nest about 8, so this is not a glTF file the loader can read: "
                       "check what wrote it");
      }
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

// A JSON value in a message: a number as itself, anything else by its JSON type alone (an
// array or string may be megabytes long or nested beyond any stack).
std::string describe(const Json& j) {
  if (j.is_number()) return j.dump();
  const std::string type = j.type_name();
  return (type == "array" || type == "object" ? "an " : "a ") + type;
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
         bad + "header says " + str(length) + " bytes, file has " + str(bytes.size()) + ": " + kDamaged);
  }
  bytes.resize(length);
  std::uint64_t json_length = read_u32_le(&bytes[12]);
  std::uint64_t json_end = 20 + json_length;
  if (read_u32_le(&bytes[16]) != 0x4E4F534Au || json_length == 0 || json_end > length) {
    fail(file, bad + "the JSON chunk is missing or runs past the end: " + kDamaged);
  }
  if (json_length % 4 != 0) fail(file, bad + "the JSON chunk is not padded to 4 bytes: " + kReexport);
  if (json_end < length) {  // a BIN chunk follows
    if (json_end + 8 > length || json_end + 8 + read_u32_le(&bytes[json_end]) > length) {
      fail(file, bad + "the BIN chunk runs past the end of the file: " + kDamaged);
    }
  }
  return std::string(bytes.begin() + 20, bytes.begin() + std::ptrdiff_t(json_end));
}

// Integers that tinygltf would silently truncate or drop: sizes must be unsigned, every
// other integer must fit an int. Also bounds the nesting (tinygltf recurses into it).
void check_numbers(const Json& j, const std::string& where, int depth, bool in_extras,
                   const std::string& file) {
  if (depth > kMaxJsonDepth) fail(file, where + " is nested too deeply: " + kReexport);  // check_nesting did
  if (j.is_object() || j.is_array()) {
    std::size_t i = 0;
    for (auto it = j.begin(); it != j.end(); ++it, ++i) {
      bool object = j.is_object();
      std::string w =
          object ? (where.empty() ? it.key() : where + "." + it.key()) : where + "[" + str(i) + "]";
      bool extras = in_extras || (object && it.key() == "extras");
      if (object && !extras && kSizeKeys.count(it.key())) {
        if (!it->is_number_unsigned()) {
          fail(file, w + " must be a non-negative integer, is " + describe(*it) + ": " + kReexport);
        }
        continue;
      }
      check_numbers(*it, w, depth + 1, extras, file);
    }
  } else if (j.is_number_integer() && !in_extras) {
    bool fits = j.is_number_unsigned() ? j.get<std::uint64_t>() <= std::uint64_t(INT_MAX)
                                       : j.get<std::int64_t>() >= INT_MIN && j.get<std::int64_t>() <= INT_MAX;
    if (!fits) {
      fail(file, where + " = " + j.dump() + " is out of range: this renderer (tinygltf) reads integers from " +
                     std::to_string(INT_MIN) + " to " + std::to_string(INT_MAX) + " there");
    }
  }
}

void check_int_size(const Json& object, const char* key, const std::string& where, const std::string& file) {
  auto value = object.find(key);
  if (value != object.end() && value->is_number_unsigned() && value->get<std::uint64_t>() > INT_MAX) {
    fail(file, where + "." + key + " = " + value->dump() + " is out of range: this renderer (tinygltf) reads it "
               "as an int, up to " + std::to_string(INT_MAX));
  }
}

// tinygltf reads a sparse accessor's count and byteOffsets into an int: larger ones would wrap.
void check_sparse_sizes(const Json& doc, const std::string& file) {
  auto accessors = doc.find("accessors");
  if (accessors == doc.end() || !accessors->is_array()) return;
  for (std::size_t i = 0; i < accessors->size(); ++i) {
    auto sparse = (*accessors)[i].find("sparse");
    if (sparse == (*accessors)[i].end() || !sparse->is_object()) continue;
    std::string where = "accessors[" + str(i) + "].sparse";
    check_int_size(*sparse, "count", where, file);
    for (const char* part : {"indices", "values"}) {
      auto array = sparse->find(part);
      if (array != sparse->end() && array->is_object())
        check_int_size(*array, "byteOffset", where + "." + part, file);
    }
  }
}

}  // namespace

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
  if (is_lfs_pointer(source.bytes.data(), source.bytes.size())) {
    fail(path, "is a Git LFS pointer, not the glTF file itself: " + kLfsAdvice);
  }
  source.base_dir = fs::path(path).parent_path().string();
  std::string text =
      source.binary ? glb_json(source.bytes, path) : std::string(source.bytes.begin(), source.bytes.end());
  check_nesting(text, path);
  Json doc;
  try {
    doc = Json::parse(text);
  } catch (const Json::exception& e) {
    std::string what = e.what();  // may quote raw bytes of the file: keep printable ASCII
    for (char& c : what) c = (c >= ' ' && c <= '~') ? c : '?';
    fail(path, "invalid JSON (" + what + "): the file is damaged or not glTF; re-export it");
  }
  if (!doc.is_object()) fail(path, "invalid JSON for glTF: the top level is not an object; re-export it");
  check_required_extensions(doc, path);
  check_numbers(doc, "", 0, false, path);
  check_sparse_sizes(doc, path);
  check_uris(doc, source.base_dir, path);
  check_image_views(doc, path);
  return source;
}

}  // namespace pt::gltf
