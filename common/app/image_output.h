// Image output (the contract (README.md), --out): .exr linear float32 RGB radiance and the
// film's channels (film_file.h), written by OpenEXR (exr_file.h); .png 8-bit sRGB (exposure,
// then clamp) and .hdr RGBE, encoded by OpenImageIO (common/base/openimageio.h). The target is checked before the
// render starts and replaced atomically after it (replace_file.h), so a failed run never
// leaves a broken file and never destroys the old one.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/app/film_file.h"

namespace pt {

struct ImageMetadata {
  std::string stage;    // e.g. "stage1_raycast"
  std::string backend;  // "cpu" or "gpu", with the device
  std::string scene;    // --scene as given
  std::uint64_t spp = 0;
  std::uint32_t seed = 0;
  double seconds = 0.0;
  // An .exr also carries the film, so that parts of one render merge (film_file.h): its
  // sums, what identifies the render, and the samples it holds. nullptr: RGB only.
  const Film* film = nullptr;
  FilmIdentity identity;
  std::vector<SampleRange> ranges;
  // --keep-halves: also the first half's luminance sums where the film knows its halves
  // (film_file.h), for pt_compare; off, an .exr has the same channels however it was split.
  bool keep_halves = false;
};

class OutputFile {
 public:
  // Checks the extension and the name's length (exit 2), that `path` is not a folder, a
  // device or a FIFO (a symbolic link is written through, at its target), and that the folder
  // exists or can be made and is writable (exit 5), without touching an existing file at
  // `path`. `option` names the path in messages.
  explicit OutputFile(std::string path, std::string option = "--out");

  // Exit 2 when `other` names the same file (one output would replace the other).
  void refuse_same_as(const OutputFile& other) const;

  const std::string& path() const { return path_; }
  // Whether `path` names an .exr (the one type that carries the film).
  static bool is_exr(const std::string& path);

  // rgb: width * height * 3 linear radiance values, top row first. The file is made in
  // memory and replaces the old one atomically (replace_file.h): a failed write (a full
  // disk) exits 5 with the old file whole; a non-finite pixel is refused (exit 3).
  void write(const std::vector<float>& rgb, int width, int height, const ImageMetadata& meta,
             float exposure = 0.0f) const;

 private:
  std::string path_;
  std::string option_;     // "--out", "--error-map", ...
  std::string extension_;  // "exr", "png" or "hdr"
};

// The 8-bit sRGB encoding of a linear value after exposure (in stops), clamped.
std::uint8_t encode_srgb8(float linear, float exposure);

}  // namespace pt
