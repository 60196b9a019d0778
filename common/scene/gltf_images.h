// The images of glTF textures opened by OpenImageIO (gltf_images.cpp), for the texture
// table's decode_into (gltf_textures.cpp), which reads every image's header before any
// image's texels. Internal to the glTF loader; not part of the article: the contract's
// (README.md) "Materials" textures.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "common/base/openimageio.h"

namespace pt::gltf::detail {

// An image opened by OpenImageIO from memory: its header read, its texels not yet.
class OpenedImage {
 public:
  // Checks the bytes (PNG or JPEG, a PNG's chunks, not a Git LFS pointer) and the header
  // (1 to 4 channels, some texels, at most kMaxTextureSize a side): fail() otherwise.
  OpenedImage(std::span<const unsigned char> bytes, const std::string& file, const std::string& what);

  std::uint32_t width() const { return std::uint32_t(width_); }
  std::uint32_t height() const { return std::uint32_t(height_); }
  std::uint64_t texels() const { return std::uint64_t(width()) * height(); }

  // Reads the texels as 8-bit RGBA into out[0 .. width * height), a few rows at a time.
  void decode(std::uint32_t* out);

 private:
  std::string file_, what_;
  std::unique_ptr<ImageReader> input_;
  int width_ = 0, height_ = 0, channels_ = 0;  // the header's, read once
};

}  // namespace pt::gltf::detail
