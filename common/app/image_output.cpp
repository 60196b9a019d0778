// Atomic image output through OpenImageIO (see image_output.h).
#include "common/app/image_output.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <system_error>

#include <OpenImageIO/imageio.h>

#include "common/base/error.h"
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
// OpenImageIO picks the right writer.
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

// The film's channels of an .exr (film_file.h): after R, G, B the variance of each pixel's
// mean luminance, then the two 32-bit halves of each double sum. Returns the pixels in the
// channels' own formats (4 bytes each), for write_image(TypeDesc::UNKNOWN).
std::vector<std::uint32_t> film_channels(const std::vector<float>& rgb, const ImageMetadata& meta,
                                         OIIO::ImageSpec& spec) {
  using namespace OIIO;
  const Film& film = *meta.film;
  spec.nchannels = 3 + 1 + 8;
  spec.channelnames = {"R", "G", "B", "Y.variance"};
  spec.channelformats.assign(4, TypeDesc::FLOAT);
  for (const char* name : kFilmSumChannels) {
    for (const char* half : {".hi", ".lo"}) {
      spec.channelnames.push_back(std::string("film.") + name + half);
      spec.channelformats.push_back(TypeDesc::UINT);
    }
  }
  spec.attribute("pt:seed", std::to_string(meta.identity.seed));  // what the merge compares
  spec.attribute("pt:scene_hash", meta.identity.scene_hash);
  spec.attribute("pt:options", meta.identity.options);
  spec.attribute("pt:samples", format_ranges(meta.ranges));
  const std::size_t pixels = std::size_t(film.width()) * std::size_t(film.height());
  std::vector<std::uint32_t> out(pixels * std::size_t(spec.nchannels));
  const std::vector<double>& sums = film.sums();
  for (std::size_t p = 0; p < pixels; p++) {
    std::uint32_t* o = &out[p * std::size_t(spec.nchannels)];
    const int x = int(p % std::size_t(film.width())), y = int(p / std::size_t(film.width()));
    const float variance = film.spp() >= 2 ? float(film.sample_variance(x, y) / double(film.spp())) : 0.0f;
    std::memcpy(o, &rgb[3 * p], 3 * sizeof(float));
    std::memcpy(o + 3, &variance, sizeof variance);
    for (int k = 0; k < 4; k++) {
      std::uint64_t bits;
      std::memcpy(&bits, &sums[4 * p + std::size_t(k)], sizeof bits);
      o[4 + 2 * k] = std::uint32_t(bits >> 32);
      o[5 + 2 * k] = std::uint32_t(bits);
    }
  }
  return out;
}

}  // namespace

void OutputFile::write(const std::vector<float>& rgb, int width, int height, const ImageMetadata& meta,
                       float exposure) const {
  using namespace OIIO;
  bool png = extension_ == "png";
  ImageSpec spec(width, height, 3, png ? TypeDesc::UINT8 : TypeDesc::FLOAT);
  spec.attribute("Software", "staged unbiased path tracer, " + meta.stage);
  spec.attribute("pt:stage", meta.stage);
  spec.attribute("pt:backend", meta.backend);
  spec.attribute("pt:scene", meta.scene);
  spec.attribute("pt:spp", std::to_string(meta.spp));
  spec.attribute("pt:seed", std::to_string(meta.seed));
  spec.attribute("pt:seconds", std::to_string(meta.seconds));
  spec.attribute("ImageDescription", meta.stage + " " + meta.scene + ", " + std::to_string(meta.spp) +
                                         " spp, seed " + std::to_string(meta.seed) + ", " + meta.backend);
  if (extension_ == "exr") spec.attribute("compression", "zip");

  std::vector<std::uint8_t> bytes;
  std::vector<std::uint32_t> film;
  const void* pixels = rgb.data();
  TypeDesc format = png ? TypeDesc::UINT8 : TypeDesc::FLOAT;
  if (png) {
    bytes.resize(rgb.size());
    for (std::size_t i = 0; i < rgb.size(); i++) bytes[i] = encode_srgb8(rgb[i], exposure);
    pixels = bytes.data();
  } else if (extension_ == "exr" && meta.film) {
    film = film_channels(rgb, meta, spec);
    pixels = film.data();
    format = TypeDesc::UNKNOWN;  // each channel in its own format
  }

  fs::path tmp = temporary_name(path_, extension_);
  set_file_in_progress(tmp.c_str());  // a second Ctrl-C removes it
  auto out = ImageOutput::create(extension_);
  if (!out) fail(path_, "no " + extension_ + " writer in OpenImageIO");
  bool ok = out->open(tmp.string(), spec) && out->write_image(format, pixels) &&
            out->close();
  std::error_code ec;
  if (!ok) {
    std::string why = out->geterror();
    fs::remove(tmp, ec);
    fail(path_, why.empty() ? "the image writer failed" : why.substr(0, why.find('\n')));
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
