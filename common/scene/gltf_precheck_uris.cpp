// The checks of a glTF 2.0 file's URIs and image bufferViews before tinygltf reads it (see
// gltf_precheck_uris.h), for the loader of the contract (README.md) "Scenes": buffer and
// image URIs stay in the scene's folder (percent-decoded as tinygltf decodes them), external
// buffers exist and are not Git LFS pointers, and the bufferViews of images lie inside their
// buffers (offsets near 2^64 included: sizes are added with overflow checks).
#include "common/scene/gltf_precheck_uris.h"

#include <cctype>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "common/scene/gltf_validate.h"
#include "common/scene/gltf_validate_detail.h"

namespace pt::gltf {

using namespace detail;

namespace {

using Json = nlohmann::json;
namespace fs = std::filesystem;

bool file_is_lfs_pointer(const fs::path& path) {
  unsigned char head[sizeof kLfsPointer - 1];
  std::ifstream in(path, std::ios::binary);
  in.read(reinterpret_cast<char*>(head), sizeof head);
  return in && is_lfs_pointer(head, sizeof head);
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

const Json* element(const Json& doc, const char* array, const Json& index) {
  auto items = doc.find(array);
  if (items == doc.end() || !items->is_array() || !index.is_number_integer()) return nullptr;
  std::int64_t i = index.get<std::int64_t>();
  if (i < 0 || std::uint64_t(i) >= items->size() || !(*items)[std::size_t(i)].is_object()) return nullptr;
  return &(*items)[std::size_t(i)];
}

}  // namespace

void detail::check_uris(const Json& doc, const std::string& base_dir, const std::string& file) {
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

void detail::check_image_views(const Json& doc, const std::string& file) {
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

}  // namespace pt::gltf
