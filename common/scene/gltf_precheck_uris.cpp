// The checks of a glTF 2.0 file's URIs and image bufferViews before tinygltf reads it (see
// gltf_precheck_uris.h), for the loader of the contract (README.md) "Scenes": buffer and
// image URIs stay in the scene's folder once resolved (percent-decoded as tinygltf decodes
// them, symbolic links followed), the files they name are regular and not too large, external
// buffers exist, match their byteLength and are not Git LFS pointers, and the bufferViews of
// images lie inside their buffers (offsets near 2^64 included: sums with overflow checks).
#include "common/scene/gltf_precheck_uris.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "common/scene/gltf_validate.h"
#include "common/scene/gltf_validate_detail.h"

namespace pt::gltf {

using namespace detail;

namespace {

using Json = nlohmann::json;
namespace fs = std::filesystem;

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

bool is_absolute(const std::string& path) {
  if (path.empty()) return false;
  if (path[0] == '/' || path[0] == '\\') return true;
  return path.size() > 1 && std::isalpha((unsigned char)path[0]) && path[1] == ':';  // C:
}

// What a file that is not regular is, for messages.
const char* file_kind(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

std::string regular_file_problem(const struct stat& st) {
  if (!S_ISREG(st.st_mode)) return std::string("is ") + file_kind(st.st_mode) + ", not a regular file";
  if (std::uint64_t(st.st_size) > kMaxSceneFileBytes) {
    return "is " + str(std::uint64_t(st.st_size)) + " bytes, more than the " + str(kMaxSceneFileBytes >> 30) +
           " GiB the loader reads from one file";
  }
  return "";
}

// The byte count a base64 payload decodes to, as tinygltf's decoder counts it (it stops at
// the first character that is not base64).
std::uint64_t base64_bytes(const std::string& uri, std::size_t start) {
  std::uint64_t digits = 0;
  for (std::size_t i = start; i < uri.size(); ++i) {
    unsigned char c = (unsigned char)uri[i];
    if (!(std::isalnum(c) || c == '+' || c == '/')) break;
    ++digits;
  }
  return digits * 3 / 4;
}

// A data: URI of a buffer: tinygltf decodes it and fails with "Failed to decode 'uri'"
// (quoting all of it) unless it holds exactly byteLength bytes.
void check_data_uri(const Json& buffer, const std::string& uri, const std::string& where, const std::string& file) {
  const std::size_t comma = uri.find(',');
  if (comma == std::string::npos || comma < 7 || uri.compare(comma - 7, 7, ";base64") != 0) {
    fail(file, where + " is a data: URI that is not base64 (data:application/octet-stream;base64,...), which "
                       "glTF buffers need: " + kReexport);
  }
  auto length = buffer.find("byteLength");
  if (length == buffer.end() || !length->is_number_unsigned()) return;  // tinygltf says
  const std::uint64_t holds = base64_bytes(uri, comma + 1), stated = length->get<std::uint64_t>();
  if (holds == stated) return;
  fail(file, where.substr(0, where.size() - 4) + ".byteLength is " + str(stated) + " but its data: URI holds " +
                 str(holds) + " bytes; glTF needs them equal: set byteLength to " + str(holds) +
                 " if the data is right, else report it to the tool that wrote the file");
}

// An external buffer's file against its byteLength (tinygltf needs them equal).
void check_buffer_length(const Json& buffer, std::uint64_t size, const std::string& where, const std::string& shown,
                         const std::string& file) {
  auto length = buffer.find("byteLength");
  if (length == buffer.end() || !length->is_number_unsigned()) return;  // tinygltf says
  const std::uint64_t stated = length->get<std::uint64_t>();
  if (size == stated) return;
  const std::string name = where.substr(0, where.size() - 4);  // "buffers[0]"
  if (size < stated) {
    fail(file, shown + " holds " + str(size) + " bytes, fewer than " + name + ".byteLength " + str(stated) +
                   ": the file is truncated or belongs to another version of the scene; copy the one exported "
                   "with this .gltf");
  }
  fail(file, shown + " holds " + str(size) + " bytes, more than " + name + ".byteLength " + str(stated) +
                 " (the loader needs them equal): it is another version of the buffer; copy the one exported "
                 "with this .gltf, or set byteLength to " + str(size) + " if the file is right");
}

const Json* element(const Json& doc, const char* array, const Json& index) {
  auto items = doc.find(array);
  if (items == doc.end() || !items->is_array() || !index.is_number_integer()) return nullptr;
  std::int64_t i = index.get<std::int64_t>();
  if (i < 0 || std::uint64_t(i) >= items->size() || !(*items)[std::size_t(i)].is_object()) return nullptr;
  return &(*items)[std::size_t(i)];
}

}  // namespace

std::string detail::scene_root(const std::string& base_dir) {
  std::error_code ec;
  fs::path root = fs::canonical(base_dir.empty() ? fs::path(".") : fs::path(base_dir), ec);
  return ec ? fs::absolute(base_dir.empty() ? fs::path(".") : fs::path(base_dir)).lexically_normal().string()
            : root.string();
}

bool detail::inside_root(const std::string& path, const std::string& root) {
  fs::path rel = fs::path(path).lexically_relative(fs::path(root));
  return !rel.empty() && *rel.begin() != ".." && *rel.begin() != ".";
}

std::vector<unsigned char> detail::read_regular_file(const std::string& path,
                                                     const std::function<void(const std::string&)>& refuse) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    refuse(errno == ENOENT || errno == ENOTDIR ? "no such file" : std::string(std::strerror(errno)));
  }
  std::string problem = regular_file_problem(st);
  if (!problem.empty()) refuse(problem);
  // O_NONBLOCK: a FIFO put in the file's place after the check opens without waiting.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) refuse(std::string(std::strerror(errno)) + (errno == EACCES ? "; check its permissions" : ""));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  if (::fstat(fd, &st) != 0) refuse(std::strerror(errno));
  problem = regular_file_problem(st);
  if (!problem.empty()) refuse(problem);
  std::vector<unsigned char> bytes(std::size_t(st.st_size));
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::read(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) refuse(std::string("cannot be read: ") + std::strerror(errno));
    if (n == 0) refuse("became shorter while it was read");
    done += std::size_t(n);
  }
  return bytes;
}

namespace {

// tinygltf looks for buffers in the scene's folder, then in the working directory; only
// the scene's folder counts.
bool exists_in_scene_folder(const std::string& path, void* user_data) {
  const std::string& base = static_cast<const SceneFolder*>(user_data)->base_dir;
  if (!base.empty() && path.compare(0, base.size(), base) != 0) return false;
  std::error_code ec;
  return fs::exists(path, ec);
}

bool read_in_scene_folder(std::vector<unsigned char>* out, std::string*, const std::string& path, void* user_data) {
  const SceneFolder& folder = *static_cast<const SceneFolder*>(user_data);
  const std::string shown = "'" + path.substr(0, 120) + "'";
  std::error_code ec;
  const std::string resolved = fs::canonical(path, ec).string();
  if (ec) fail(folder.file, shown + " was not found in the scene's folder: copy it there");
  if (!inside_root(resolved, folder.root)) {
    fail(folder.file, shown + " resolves to '" + resolved.substr(0, 120) + "', outside the scene's folder '" +
                          folder.root + "': the loader reads nothing outside the folder of the scene file");
  }
  *out = read_regular_file(resolved, [&](const std::string& why) { fail(folder.file, shown + " " + why); });
  return true;
}

}  // namespace

tinygltf::FsCallbacks detail::scene_folder_callbacks(SceneFolder* folder) {
  return {&exists_in_scene_folder, &tinygltf::ExpandFilePath, &read_in_scene_folder, &tinygltf::WriteWholeFile,
          folder};
}

void detail::check_uris(const Json& doc, const std::string& base_dir, const std::string& file) {
  const std::string root = scene_root(base_dir);
  for (const char* array : {"buffers", "images"}) {
    auto items = doc.find(array);
    if (items == doc.end() || !items->is_array()) continue;
    const bool buffers = std::string(array) == "buffers";
    for (std::size_t i = 0; i < items->size(); ++i) {
      const Json& item = (*items)[i];
      if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string()) continue;
      std::string uri = item["uri"].get<std::string>();
      std::string where = std::string(array) + "[" + str(i) + "].uri";
      std::string shown = where + " '" + uri.substr(0, 80) + "'";
      if (tinygltf::IsDataURI(uri)) {
        if (buffers) check_data_uri(item, uri, where, file);
        continue;
      }
      const std::string outside = "outside the scene's folder '" + root +
                                  "': the loader reads nothing outside the folder of the scene file; copy the file "
                                  "into it (or embed it, e.g. export as .glb)";
      std::string decoded = decode_uri(uri);
      if (decoded.find('\0') != std::string::npos) fail(file, shown + " contains a NUL character: " + kReexport);
      if (is_absolute(uri) || is_absolute(decoded)) fail(file, shown + " is an absolute path, " + outside);
      // Resolved as the system opens it: symbolic links followed, "sub/../x" only where sub exists.
      fs::path path = fs::path(base_dir) / decoded;
      std::error_code ec;
      fs::path resolved = fs::canonical(path, ec);
      if (ec) {  // not there: where it would lie, for the message
        fs::path would = fs::weakly_canonical(fs::path(root) / decoded, ec);
        if (!ec && !inside_root(would.string(), root)) fail(file, shown + " points " + outside);
        if (buffers) {
          fail(file, shown + " was not found in the scene's folder: copy it there, or export the scene as .glb");
        }
        continue;  // a missing image is said only when a drawn material uses it (gltf_textures.cpp)
      }
      if (!inside_root(resolved.string(), root)) {
        fail(file, shown + " resolves to '" + resolved.string().substr(0, 120) + "', " + outside);
      }
      struct stat st {};
      if (::stat(resolved.c_str(), &st) == 0) {
        std::string problem = regular_file_problem(st);
        if (!problem.empty()) fail(file, shown + " " + problem + ": give a regular file");
      }
      if (!buffers) continue;
      unsigned char head[sizeof kLfsPointer - 1] = {};
      const int fd = ::open(resolved.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
      const ssize_t n = fd >= 0 ? ::read(fd, head, sizeof head) : -1;
      if (fd >= 0) ::close(fd);
      if (n == ssize_t(sizeof head) && is_lfs_pointer(head, sizeof head)) {
        fail(file, shown + " is a Git LFS pointer, not the buffer itself: " + kLfsAdvice);
      }
      check_buffer_length(item, std::uint64_t(st.st_size), where, shown, file);
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
      // Both indices are integers here (element() checked them): printed as numbers.
      fail(file, where + ": bufferViews[" + str(image["bufferView"].get<std::uint64_t>()) + "] runs past buffers[" +
                     str((*view)["buffer"].get<std::uint64_t>()) + "] (" + need_text(overflow, end, has) +
                     "): " + kReexport);
    }
  }
}

}  // namespace pt::gltf
