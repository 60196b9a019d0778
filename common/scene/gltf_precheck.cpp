// The checks of a glTF 2.0 file before tinygltf reads it, for the loader of the contract
// (README.md) "Scenes": the file itself (a Git LFS pointer is named as one), the GLB
// container, the JSON's integers and nesting, extensionsRequired (before tinygltf reads
// buffers an extension may have compressed), and the sizes tinygltf reads into an int; then
// buffer and image URIs and the bufferViews of images (gltf_precheck_uris.cpp).
#include <cctype>
#include <cerrno>
#include <climits>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
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
  // One read of the whole file (a byte at a time through a stream iterator took a second
  // for a 180 MB mesh).
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) {  // not seekable (a pipe): as a stream
    in.clear();
    return std::vector<unsigned char>(std::istreambuf_iterator<char>(in), {});
  }
  in.seekg(0, std::ios::beg);
  std::vector<unsigned char> bytes(size > 0 ? std::size_t(size) : 0);
  if (size > 0 && !in.read(reinterpret_cast<char*>(bytes.data()), size)) {
    throw Error(kExitBadScene,
                "cannot read scene '" + path + "': " + std::strerror(errno) + "; check the file");
  }
  return bytes;
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

void check_int_size(const Json& object, const char* key, const std::string& where, const std::string& file) {
  auto value = object.find(key);
  if (value != object.end() && value->is_number_unsigned() && value->get<std::uint64_t>() > INT_MAX) {
    fail(file, where + "." + key + " = " + value->dump() + " is out of range: " + kReexport);
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
