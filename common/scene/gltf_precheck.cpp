// The checks of a glTF 2.0 file before tinygltf reads it, for the loader of the contract
// (README.md) "Scenes": the file itself (a Git LFS pointer is named as one), the GLB
// container, the JSON's integers and nesting, extensionsRequired (before tinygltf reads
// buffers an extension may have compressed), buffer and image URIs, and the bufferViews of
// images (offsets near 2^64 included: sizes are added with overflow checks).
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
#include "common/scene/gltf_validate.h"
#include "common/scene/gltf_validate_detail.h"

namespace pt::gltf {

using namespace detail;

namespace {

using Json = nlohmann::json;
namespace fs = std::filesystem;

constexpr int kMaxJsonDepth = 64;  // real files nest about 8 levels
const std::set<std::string> kSizeKeys = {"byteOffset", "byteLength", "byteStride", "count"};
bool file_is_lfs_pointer(const fs::path& path) {
  unsigned char head[sizeof kLfsPointer - 1];
  std::ifstream in(path, std::ios::binary);
  in.read(reinterpret_cast<char*>(head), sizeof head);
  return in && is_lfs_pointer(head, sizeof head);
}

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

// Buffer and image URIs stay inside the scene's folder; external buffers must exist and
// hold data, not a Git LFS pointer.
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
      if (std::string(array) != "buffers") continue;
      std::error_code ec;
      fs::path path = fs::path(base_dir) / decoded;
      if (!fs::is_regular_file(path, ec)) {
        fail(file, where + " '" + uri.substr(0, 80) +
                       "' was not found next to the scene: copy it there or re-export as .glb");
      }
      if (file_is_lfs_pointer(path)) {
        fail(file, where + " '" + uri.substr(0, 80) +
                       "' is a Git LFS pointer, not the buffer itself: " + kLfsAdvice);
      }
    }
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
