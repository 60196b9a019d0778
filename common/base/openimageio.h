// OpenImageIO, loaded the first time an image is decoded or a PNG or HDR is written, not at
// program start. Linking it directly maps its ~260 shared libraries into every run: 0.33 s
// of CPU per process, which a render of a few seconds, a lab's quick check and each part
// of a split frame (docs/film.md) all paid. The .exr film files go through OpenEXR itself
// (common/app/exr_file.h), so a render to .exr never loads OpenImageIO at all.
// The library sits in a module beside the program (pt_openimageio.so, built from
// openimageio_module.cpp); this header is all the rest of the code sees of it.
// Not part of the article: machinery for image files.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace pt {

// A PNG or JPEG opened from memory: its header read, its texels not yet.
class ImageReader {
 public:
  virtual ~ImageReader() = default;
  virtual int width() const = 0;
  virtual int height() const = 0;
  virtual int depth() const = 0;
  virtual int channels() const = 0;
  // Rows y0 .. y1 - 1 as 8-bit values, channels() per texel; false: error() says why.
  virtual bool read_rows(int y0, int y1, unsigned char* out) = 0;
  virtual std::string error() const = 0;
};

using ImageAttributes = std::vector<std::pair<std::string, std::string>>;

class ImageCodec {
 public:
  virtual ~ImageCodec() = default;
  // Opens `size` bytes of a PNG (png) or JPEG (!png) that outlive the reader; straight
  // (unassociated) alpha is kept as stored. nullptr: `why` says why.
  virtual std::unique_ptr<ImageReader> open_memory(const unsigned char* bytes, std::size_t size, bool png,
                                                   std::string& why) const = 0;
  // Encodes an RGB image in memory, in the format that `extension` names ("png": 8-bit
  // values, "hdr": floats), with text attributes: `bytes` is then the whole file, which
  // common/app/replace_file.h writes (OpenImageIO's writers do not report a short write).
  // false: `why` says why.
  virtual bool encode_rgb(const std::string& extension, int width, int height, const void* pixels,
                          const ImageAttributes& attributes, std::vector<unsigned char>& bytes,
                          std::string& why) const = 0;
  // Reads the image file `path` (an .hdr or .exr environment map: issue #49) as float RGB,
  // rows from the image's top: a grey image is repeated into R, G and B, a fourth channel
  // dropped. false: `why` says why.
  virtual bool read_float_rgb(const std::string& path, int& width, int& height, std::vector<float>& rgb,
                              std::string& why) const = 0;
};

// The module's one entry point (extern "C", so dlsym finds it by this name).
#define PT_IMAGE_CODEC_ENTRY "pt_image_codec"
using ImageCodecEntry = const ImageCodec* (*)();

// OpenImageIO, loaded from the module beside the running program on the first call. nullptr
// when it cannot be loaded: `why` names the module and the loader's reason.
const ImageCodec* openimageio(std::string& why);

}  // namespace pt
