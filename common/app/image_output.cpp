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
#include "common/base/error.h"
#include "common/base/openimageio.h"
#include "common/render/interrupt.h"

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

// A temporary name beside the target, ending in the target's extension so that
// the writer is the right one.
fs::path temporary_name(const std::string& path, const std::string& ext) {
  fs::path p(path);
  return folder_of(path) / ("." + p.filename().string() + ".tmp" + std::to_string(::getpid()) + "." + ext);
}

void fail(const std::string& path, const std::string& why) {
  throw Error(kExitOutput, "cannot write '" + path + "': " + why +
                               "; choose another --out path or fix the folder's permissions");
}

}  // namespace

OutputFile::OutputFile(std::string path) : path_(std::move(path)), extension_(lower_extension(path_)) {
  if (extension_ != "exr" && extension_ != "png" && extension_ != "hdr") {
    throw Error(kExitBadOption, "--out '" + path_ + "': unknown image type '." + extension_ +
                                    "'; use a name ending in .exr, .png or .hdr");
  }
  if (fs::is_directory(path_)) fail(path_, "it is a folder");
  if (extension_ != "exr") {  // its writer is OpenImageIO's module: found now, not after the render
    std::string why;
    if (!openimageio(why)) throw Error(kExitOutput, "cannot write '" + path_ + "': " + why);
  }
  std::error_code ec;
  fs::path folder = folder_of(path_);
  fs::create_directories(folder, ec);
  if (ec || !fs::is_directory(folder)) fail(path_, "its folder cannot be created (" + ec.message() + ")");
  // Prove the folder takes a new file now, rather than after an hour of rendering.
  fs::path probe = temporary_name(path_, extension_);
  int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
  if (fd < 0) fail(path_, std::string("its folder is not writable (") + std::strerror(errno) + ")");
  ::close(fd);
  fs::remove(probe, ec);
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
  return image;
}

}  // namespace

void OutputFile::write(const std::vector<float>& rgb, int width, int height, const ImageMetadata& meta,
                       float exposure) const {
  ImageAttributes text = {
      {"Software", "staged unbiased path tracer, " + meta.stage},
      {"pt:stage", meta.stage},
      {"pt:backend", meta.backend},
      {"pt:scene", meta.scene},
      {"pt:spp", std::to_string(meta.spp)},
      {"pt:seed", std::to_string(meta.film ? meta.identity.seed : meta.seed)},  // a film's: what the merge compares
      {"pt:seconds", std::to_string(meta.seconds)},
  };
  const std::string description = meta.stage + " " + meta.scene + ", " + std::to_string(meta.spp) + " spp, seed " +
                                  std::to_string(meta.seed) + ", " + meta.backend;

  fs::path tmp = temporary_name(path_, extension_);
  set_file_in_progress(tmp.c_str());  // a second Ctrl-C removes it
  std::string why;
  bool ok;
  if (extension_ == "exr") {
    ExrImage image = exr_image(rgb, width, height, meta);
    image.text.insert(image.text.begin(), text.begin(), text.end());
    image.text.emplace_back("comments", description);  // EXR's own name for a description
    ok = write_exr(tmp.string(), image, why);
  } else {
    const ImageCodec* codec = openimageio(why);
    if (!codec) {
      set_file_in_progress("");
      throw Error(kExitOutput, "cannot write '" + path_ + "': " + why);
    }
    text.emplace_back("ImageDescription", description);
    std::vector<std::uint8_t> bytes;
    if (extension_ == "png") {
      bytes.resize(rgb.size());
      for (std::size_t i = 0; i < rgb.size(); i++) bytes[i] = encode_srgb8(rgb[i], exposure);
    }
    const void* pixels = bytes.empty() ? static_cast<const void*>(rgb.data()) : bytes.data();
    ok = codec->write_rgb(tmp.string(), extension_, width, height, pixels, text, why);
  }
  std::error_code ec;
  if (!ok) {
    fs::remove(tmp, ec);
    fail(path_, why.substr(0, why.find('\n')));
  }
  // Flush to the disk before the rename, so the target is the old file or the whole new one.
  int fd = ::open(tmp.c_str(), O_RDONLY);
  if (fd >= 0) ::fsync(fd), ::close(fd);
  fs::rename(tmp, path_, ec);
  set_file_in_progress("");
  if (ec) {
    std::string why = ec.message();
    fs::remove(tmp, ec);
    fail(path_, "renaming the finished image failed (" + why + ")");
  }
}

}  // namespace pt
