// The .exr files of the film (film_file.h), read and written by OpenEXR itself: 32-bit
// channels (floats, and the unsigned halves of the film's double sums) and text attributes.
// OpenEXR is the library under OpenImageIO's EXR support; using it directly keeps
// OpenImageIO's 0.33 s of start-up out of every render to .exr and every merge
// (common/base/openimageio.h). Not part of the article: machinery for the film's file.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace pt {

struct ExrImage {
  int width = 0, height = 0;
  std::vector<std::string> channels;  // names, in the order of the interleaved pixels
  std::vector<bool> is_uint;          // per channel: 32-bit unsigned integers, else 32-bit floats
  std::vector<std::uint32_t> pixels;  // width * height * channels.size() values (float bits or integers), top row first
  std::vector<std::pair<std::string, std::string>> text;  // string attributes

  // The index of a channel, or -1.
  int channel(const std::string& name) const;
  // A string attribute's value, or "" when there is none.
  std::string attribute(const std::string& name) const;
  // Sets a string attribute ("" removes it).
  void set_attribute(const std::string& name, const std::string& value);
};

// The bytes of `image` as an .exr file with ZIP compression, made in memory (so that the
// file is written by replace_file.h, which checks every write). false: `why` says why in one line.
bool encode_exr(const ExrImage& image, std::vector<char>& bytes, std::string& why);

// encode_exr(), then replace_file() over `path`. false: `why` says why in one line.
bool write_exr(const std::string& path, const ExrImage& image, std::string& why);

// Reads every channel of a scanline or tiled single-part EXR (a half channel as floats) and
// its string attributes. false: `why` says why in one line.
bool read_exr(const std::string& path, ExrImage& image, std::string& why);

}  // namespace pt
