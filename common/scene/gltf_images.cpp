// glTF images (see gltf_textures.h and gltf_images.h): tinygltf's image loader, which only
// keeps the bytes, and the images decoded by OpenImageIO from memory (PNG or JPEG; never by
// tinygltf; OpenImageIO is loaded then, common/base/openimageio.h): a PNG's chunks checked
// first, each image's header against kMaxTextureSize, libpng's own stderr silenced.
// Not part of the article: the contract's (README.md) "Materials" textures.
#include "common/scene/gltf_images.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <vector>

#include "common/scene/gltf_textures.h"
#include "common/scene/gltf_validate.h"
#include "common/scene/gltf_validate_detail.h"

namespace pt::gltf {

using namespace detail;

namespace {

// OpenImageIO's error text made short enough for a one-line message.
std::string short_error(std::string why) {
  for (char& c : why) c = (c == '\n' || c == '\r') ? ' ' : c;
  while (!why.empty() && (why.back() == ' ' || why.back() == '.')) why.pop_back();
  if (why.size() > 160) why = why.substr(0, 160) + "...";
  return why.empty() ? "no reason given" : why;
}

bool starts_with(std::span<const unsigned char> bytes, const char* magic, std::size_t n) {
  return bytes.size() >= n && std::memcmp(bytes.data(), magic, n) == 0;
}

// CRC-32 of PNG chunks (ISO 3309, as zlib's crc32).
std::uint32_t crc32(const unsigned char* p, std::size_t n, std::uint32_t crc = 0xffffffffu) {
  for (std::size_t i = 0; i < n; ++i) {
    crc ^= p[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return crc;
}

// The chunks of a PNG, checked before libpng sees them: each within the data with its CRC
// right, IHDR first, IEND last. libpng prints its own line on stderr for a damaged chunk
// before OpenImageIO reports it; this check names the damage in the one line instead.
void check_png_chunks(std::span<const unsigned char> bytes, const std::string& file, const std::string& what) {
  std::size_t at = 8;
  bool first = true;
  while (true) {
    if (bytes.size() - at < 12) {
      fail(file, what + " is a truncated PNG (no IEND chunk at its end): re-export it");
    }
    const unsigned char* c = bytes.data() + at;
    const std::uint64_t length = std::uint64_t(c[0]) << 24 | std::uint64_t(c[1]) << 16 | std::uint64_t(c[2]) << 8 | c[3];
    const std::string type(reinterpret_cast<const char*>(c + 4), 4);
    if (length > bytes.size() - at - 12) {
      fail(file, what + " is a truncated PNG (its chunk at byte " + str(at) + " runs past the end): re-export it");
    }
    const unsigned char* crc = c + 8 + length;
    const std::uint32_t stored = std::uint32_t(crc[0]) << 24 | std::uint32_t(crc[1]) << 16 | std::uint32_t(crc[2]) << 8 | crc[3];
    if ((crc32(c + 4, std::size_t(length) + 4) ^ 0xffffffffu) != stored) {
      fail(file, what + " is a damaged PNG (the CRC of its chunk at byte " + str(at) + " is wrong): re-export it");
    }
    if (first && type != "IHDR") fail(file, what + " is a damaged PNG (it does not start with IHDR): re-export it");
    first = false;
    at += 12 + std::size_t(length);
    if (type == "IEND") return;
  }
}

// libpng writes its errors on stderr itself as well as handing them to OpenImageIO, which
// hands them to us: while OpenImageIO reads, file descriptor 2 goes to /dev/null, so that a
// damaged image gives only fail()'s one line. The scene loads before any render thread
// starts, so nothing else is writing then.
class QuietStderr {
 public:
  QuietStderr() {
    std::fflush(stderr);
    saved_ = ::dup(2);
    const int null = ::open("/dev/null", O_WRONLY);
    if (saved_ >= 0 && null >= 0) ::dup2(null, 2);
    if (null >= 0) ::close(null);
  }
  ~QuietStderr() {
    if (saved_ < 0) return;
    std::fflush(stderr);
    ::dup2(saved_, 2);
    ::close(saved_);
  }
  QuietStderr(const QuietStderr&) = delete;
  QuietStderr& operator=(const QuietStderr&) = delete;

 private:
  int saved_ = -1;
};

}  // namespace

detail::OpenedImage::OpenedImage(std::span<const unsigned char> bytes, const std::string& file,
                                 const std::string& what)
    : file_(file), what_(what) {
  const bool png = starts_with(bytes, "\x89PNG\r\n\x1a\n", 8), jpeg = starts_with(bytes, "\xff\xd8\xff", 3);
  if (detail::is_lfs_pointer(bytes.data(), bytes.size())) {
    fail(file, what + " is a Git LFS pointer, not the image itself: " + detail::kLfsAdvice);
  }
  if (!png && !jpeg) {
    fail(file, what + " is neither a PNG nor a JPEG image: glTF images are PNG or JPEG; convert it and re-export");
  }
  if (png) check_png_chunks(bytes, file, what);
  std::string why;
  const ImageCodec* codec = openimageio(why);
  if (!codec) fail(file, what + ": " + why);
  {
    QuietStderr quiet;
    input_ = codec->open_memory(bytes.data(), bytes.size(), png, why);
  }
  if (!input_) {
    fail(file, what + " cannot be decoded (" + short_error(why) + "): the image is damaged or truncated; re-export it");
  }
  width_ = input_->width(), height_ = input_->height(), channels_ = input_->channels();
  if (channels_ < 1 || channels_ > 4) {
    fail(file, what + " has " + std::to_string(channels_) +
                   " channels; glTF images have 1 to 4: convert it to RGB or RGBA and re-export");
  }
  if (width_ <= 0 || height_ <= 0 || input_->depth() != 1) {
    fail(file, what + " has no texels (" + std::to_string(width_) + " x " + std::to_string(height_) +
                   "): re-export it");
  }
  if (std::uint64_t(width_) > kMaxTextureSize || std::uint64_t(height_) > kMaxTextureSize) {
    fail(file, what + " is " + std::to_string(width_) + " x " + std::to_string(height_) +
                   " texels, more than the " + std::to_string(kMaxTextureSize) + " x " +
                   std::to_string(kMaxTextureSize) + " an image may have: downscale it and re-export");
  }
}

void detail::OpenedImage::decode(std::uint32_t* out) {
  const int channels = channels_;
  const int rows_per_read = 64;
  std::vector<unsigned char> rows(std::size_t(width_) * channels * rows_per_read);
  for (int y0 = 0; y0 < height_; y0 += rows_per_read) {
    const int y1 = std::min(height_, y0 + rows_per_read);
    bool read;
    {
      QuietStderr quiet;
      read = input_->read_rows(y0, y1, rows.data());
    }
    if (!read) {
      fail(file_, what_ + " cannot be decoded (" + short_error(input_->error()) +
                      "): the image is damaged or truncated; re-export it");
    }
    const std::size_t n = std::size_t(y1 - y0) * std::size_t(width_);
    for (std::size_t i = 0; i < n; ++i) {
      const unsigned char* p = &rows[i * channels];
      std::uint32_t r = p[0], g = channels >= 3 ? p[1] : p[0], b = channels >= 3 ? p[2] : p[0];
      std::uint32_t a = channels == 2 ? p[1] : channels == 4 ? p[3] : 255u;
      out[std::size_t(y0) * std::size_t(width_) + i] = r | g << 8 | b << 16 | a << 24;
    }
  }
}

bool keep_image_bytes(tinygltf::Image* image, int, std::string*, std::string*, int, int, const unsigned char* bytes,
                      int size, void*) {
  if (image->bufferView == -1 && bytes && size > 0) image->image.assign(bytes, bytes + size);
  return true;
}

DecodedImage decode_image(std::span<const unsigned char> bytes, const std::string& file, const std::string& what) {
  OpenedImage opened(bytes, file, what);
  DecodedImage image{opened.width(), opened.height(), std::vector<std::uint32_t>(opened.texels())};
  opened.decode(image.texels.data());
  return image;
}

}  // namespace pt::gltf
