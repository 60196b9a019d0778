// Atomic image output (see image_output.h): .exr through OpenEXR (exr_file.h), .png and
// .hdr through OpenImageIO, loaded only then (common/base/openimageio.h).
#include "common/app/image_output.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "common/app/exr_file.h"
#include "common/app/replace_file.h"
#include "common/base/error.h"
#include "common/base/openimageio.h"

namespace pt {
namespace fs = std::filesystem;

namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  if (!ext.empty()) ext.erase(0, 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

fs::path folder_of(const std::string& path) {
  fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? fs::path(".") : parent;
}

void fail(const std::string& path, const std::string& why, const std::string& todo) {
  throw Error(kExitOutput, "cannot write '" + path + "': " + why + "; " + todo);
}

}  // namespace

OutputFile::OutputFile(std::string path, std::string option)
    : path_(std::move(path)), option_(std::move(option)), extension_(lower_extension(path_)) {
  if (extension_ != "exr" && extension_ != "png" && extension_ != "hdr") {
    throw Error(kExitBadOption, option_ + " '" + path_ + "': unknown image type '." + extension_ +
                                    "'; use a name ending in .exr, .png or .hdr");
  }
  const std::string name = fs::path(path_).filename().string();
  if (name.size() > 255) {
    throw Error(kExitBadOption, option_ + " '" + path_.substr(0, 60) + "...': its file name is " +
                                    std::to_string(name.size()) + " bytes, longer than the 255 a file system takes; "
                                    "choose a shorter name");
  }
  const std::string target = output_target(path_, option_);  // a folder, device or FIFO: exit 5
  if (extension_ != "exr") {  // its writer is OpenImageIO's module: found now, not after the render
    std::string why;
    if (!openimageio(why)) throw Error(kExitOutput, "cannot write '" + path_ + "': " + why);
  }
  std::error_code ec;
  fs::path folder = folder_of(target);
  fs::create_directories(folder, ec);
  if (ec || !fs::is_directory(folder)) {
    fail(path_, "its folder cannot be created (" + ec.message() + ")", "choose another " + option_ + " path");
  }
  // Prove the folder takes a new file now, rather than after an hour of rendering.
  const std::string probe = temporary_path(target, long(::getpid()));
  int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) {
    fail(path_, std::string("its folder is not writable (") + std::strerror(errno) + ")",
         "choose another " + option_ + " path or fix the folder's permissions");
  }
  ::close(fd);
  ::unlink(probe.c_str());
}

void OutputFile::refuse_same_as(const OutputFile& other) const {
  if (same_file(path_, other.path_)) {
    throw Error(kExitBadOption, option_ + " '" + path_ + "' is the same file as " + other.option_ + " '" +
                                    other.path_ + "'; give each output its own name");
  }
}

bool OutputFile::is_exr(const std::string& path) { return lower_extension(path) == "exr"; }

std::uint8_t encode_srgb8(float linear, float exposure) {
  float v = linear * std::exp2(exposure);
  if (!(v > 0.0f)) return 0;  // also NaN
  if (v >= 1.0f) return 255;
  float s = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
  return std::uint8_t(std::lround(s * 255.0f));
}

namespace {

// An .exr's channels: R, G, B, and for a film (film_file.h) the variance of each pixel's
// mean luminance, then the two 32-bit halves of each double sum, and where the film knows the
// halves of its samples (Film::has_halves) the first half's luminance sums the same way.
ExrImage exr_image(const std::vector<float>& rgb, int width, int height, const ImageMetadata& meta) {
  ExrImage image;
  image.width = width, image.height = height;
  image.channels = {"R", "G", "B"};
  const bool halves = meta.keep_halves && meta.film && meta.film->has_halves() && meta.ranges.size() == 1;
  if (meta.film) {
    image.channels.push_back("Y.variance");
    for (const char* name : kFilmSumChannels) {
      for (const char* half : {".hi", ".lo"}) image.channels.push_back(std::string("film.") + name + half);
    }
    image.text.emplace_back("pt:scene_hash", meta.identity.scene_hash);  // what the merge compares
    image.text.emplace_back("pt:options", meta.identity.options);
    image.text.emplace_back("pt:samples", format_ranges(meta.ranges));
  }
  if (halves) {
    for (const char* half : {".hi", ".lo"}) image.channels.push_back(std::string("film.") + kFilmHalfChannel + half);
    image.text.emplace_back("pt:halves", format_ranges({{meta.ranges.front().first, meta.film->first_half_spp()}}));
  }
  const std::size_t n = image.channels.size();
  image.is_uint.assign(n, false);
  for (std::size_t c = 4; c < n; c++) image.is_uint[c] = true;
  const std::size_t pixels = std::size_t(width) * std::size_t(height);
  image.pixels.resize(pixels * n);
  for (std::size_t p = 0; p < pixels; p++) {
    std::uint32_t* o = &image.pixels[p * n];
    std::memcpy(o, &rgb[3 * p], 3 * sizeof(float));
    if (!meta.film) continue;
    const Film& film = *meta.film;
    const int x = int(p % std::size_t(width)), y = int(p / std::size_t(width));
    const float variance = film.spp() >= 2 ? float(film.sample_variance(x, y) / double(film.spp())) : 0.0f;
    std::memcpy(o + 3, &variance, sizeof variance);
    for (int k = 0; k < 4; k++) split_double(film.sums()[4 * p + std::size_t(k)], o[4 + 2 * k], o[5 + 2 * k]);
    if (halves) split_double(film.first_half_luminance()[p], o[12], o[13]);
  }
  if (meta.film) image.text.emplace_back(kFilmChecksumAttribute, film_checksum(image, meta.stage, std::to_string(meta.seed)));
  return image;
}

}  // namespace

namespace {

// The pixels' first non-finite value (+Inf from a float overflow, NaN), as an error.
void refuse_non_finite(const std::vector<float>& rgb, int width, const std::string& path) {
  std::size_t count = 0, first = 0;
  for (std::size_t i = 0; i < rgb.size(); i += 3) {
    if (std::isfinite(rgb[i]) && std::isfinite(rgb[i + 1]) && std::isfinite(rgb[i + 2])) continue;
    if (count++ == 0) first = i / 3;
  }
  if (count == 0) return;
  throw Error(kExitBadScene, "not writing '" + path + "': " +
                                 (count == 1 ? std::string("1 pixel is not a finite number")
                                             : std::to_string(count) + " pixels are not finite numbers") +
                                 " (the first at x " + std::to_string(first % std::size_t(width)) +
                                 ", y " + std::to_string(first / std::size_t(width)) +
                                 "): the scene's radiance overflows a float; lower its emission or light intensity");
}

}  // namespace

void OutputFile::write(const std::vector<float>& rgb, int width, int height, const ImageMetadata& meta,
                       float exposure) const {
  refuse_non_finite(rgb, width, path_);
  ImageAttributes text = {
      {"Software", "staged unbiased path tracer, " + meta.stage},
      {"pt:stage", meta.stage},
      {"pt:backend", meta.backend},
      {"pt:scene", meta.scene},
      {"pt:spp", std::to_string(meta.spp)},
      {"pt:seed", std::to_string(meta.seed)},
      {"pt:seconds", std::to_string(meta.seconds)},
  };
  const std::string description = meta.stage + " " + meta.scene + ", " + std::to_string(meta.spp) + " spp, seed " +
                                  std::to_string(meta.seed) + ", " + meta.backend;

  // The whole file in memory first; replace_file() then writes it, checking every write.
  std::string why;
  std::vector<char> exr_bytes;
  std::vector<unsigned char> bytes;
  bool ok;
  if (extension_ == "exr") {
    ExrImage image = exr_image(rgb, width, height, meta);
    image.text.insert(image.text.begin(), text.begin(), text.end());
    image.text.emplace_back("comments", description);  // EXR's own name for a description
    ok = encode_exr(image, exr_bytes, why);
  } else {
    const ImageCodec* codec = openimageio(why);
    if (!codec) throw Error(kExitOutput, "cannot write '" + path_ + "': " + why);
    text.emplace_back("ImageDescription", description);
    std::vector<std::uint8_t> srgb;
    if (extension_ == "png") {
      srgb.resize(rgb.size());
      for (std::size_t i = 0; i < rgb.size(); i++) srgb[i] = encode_srgb8(rgb[i], exposure);
    }
    const void* pixels = srgb.empty() ? static_cast<const void*>(rgb.data()) : srgb.data();
    ok = codec->encode_rgb(extension_, width, height, pixels, text, bytes, why);
  }
  if (!ok) fail(path_, why.substr(0, why.find('\n')), "choose another " + option_ + " path or image type");
  const ByteSpan span = exr_bytes.empty() ? ByteSpan{bytes.data(), bytes.size()} : ByteSpan{exr_bytes.data(), exr_bytes.size()};
  replace_file(path_, {span}, "free some space or choose another " + option_ + " path");
}

}  // namespace pt
