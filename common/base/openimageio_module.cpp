// The module pt_openimageio.so (see openimageio.h): OpenImageIO behind the ImageCodec
// interface, decoding glTF's PNG and JPEG textures from memory and writing .png and .hdr
// images. Loaded by openimageio() on first use; nothing else links OpenImageIO.
#include <memory>
#include <string>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "common/base/openimageio.h"

namespace pt {
namespace {

class OiioReader final : public ImageReader {
 public:
  OiioReader(std::unique_ptr<OIIO::Filesystem::IOMemReader> memory, std::unique_ptr<OIIO::ImageInput> input,
             OIIO::ImageSpec spec)
      : memory_(std::move(memory)), input_(std::move(input)), spec_(std::move(spec)) {}
  ~OiioReader() override { input_->close(); }

  int width() const override { return spec_.width; }
  int height() const override { return spec_.height; }
  int depth() const override { return spec_.depth; }
  int channels() const override { return spec_.nchannels; }
  bool read_rows(int y0, int y1, unsigned char* out) override {
    return input_->read_scanlines(0, 0, spec_.y + y0, spec_.y + y1, 0, 0, spec_.nchannels, OIIO::TypeDesc::UINT8, out);
  }
  std::string error() const override { return input_->geterror(); }

 private:
  std::unique_ptr<OIIO::Filesystem::IOMemReader> memory_;  // outlives input_ (declared first)
  std::unique_ptr<OIIO::ImageInput> input_;
  OIIO::ImageSpec spec_;
};

class OiioCodec final : public ImageCodec {
 public:
  std::unique_ptr<ImageReader> open_memory(const unsigned char* bytes, std::size_t size, bool png,
                                           std::string& why) const override {
    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::create(png ? "png" : "jpeg");
    if (!input) {
      why = std::string("OpenImageIO has no ") + (png ? "PNG" : "JPEG") + " reader (" + OIIO::geterror() +
            "); install its plugins";
      return nullptr;
    }
    auto memory = std::make_unique<OIIO::Filesystem::IOMemReader>(bytes, size);
    input->set_ioproxy(memory.get());
    OIIO::ImageSpec config, spec;
    config.attribute("oiio:UnassociatedAlpha", 1);  // glTF's alpha is straight: keep the colour as stored
    if (!input->open(png ? "image.png" : "image.jpg", spec, config)) {
      why = input->geterror();
      return nullptr;
    }
    return std::make_unique<OiioReader>(std::move(memory), std::move(input), std::move(spec));
  }

  bool encode_rgb(const std::string& extension, int width, int height, const void* pixels,
                  const ImageAttributes& attributes, std::vector<unsigned char>& bytes, std::string& why) const override {
    const OIIO::TypeDesc format = extension == "png" ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT;
    OIIO::ImageSpec spec(width, height, 3, format);
    for (const auto& [name, value] : attributes) spec.attribute(name, value);
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(extension);
    if (!out || !out->supports("ioproxy")) {
      why = "no " + extension + " writer into memory in OpenImageIO";
      return false;
    }
    bytes.clear();
    OIIO::Filesystem::IOVecOutput memory(bytes);
    out->set_ioproxy(&memory);
    if (out->open("image." + extension, spec) && out->write_image(format, pixels) && out->close()) return true;
    why = out->geterror();
    if (why.empty()) why = "the image writer failed";
    return false;
  }

  bool read_float_rgb(const std::string& path, int& width, int& height, std::vector<float>& rgb,
                      std::string& why) const override {
    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(path);
    if (!input) {
      why = OIIO::geterror();
      if (why.empty()) why = "OpenImageIO cannot open it";
      return false;
    }
    const OIIO::ImageSpec& spec = input->spec();
    width = spec.width, height = spec.height;
    const int channels = spec.nchannels;
    if (width <= 0 || height <= 0 || channels <= 0 || spec.depth > 1) {
      why = "it holds no 2D image";
      return false;
    }
    // A header's size is checked before the texels are allocated (a damaged or forged file).
    if (width > 65536 || height > 32768) {
      why = "its header says " + std::to_string(width) + " x " + std::to_string(height) +
            " texels, more than an environment map may have (65536 x 32768)";
      return false;
    }
    // Every channel (OpenEXR reads a subset of them slower than all), then the first three
    // into rgb; a grey image's one channel into R, G and B. An RGB image is read in place.
    const std::size_t n = std::size_t(width) * std::size_t(height);
    rgb.resize(3 * n);
    std::vector<float> all(channels == 3 ? 0 : n * std::size_t(channels));
    if (!input->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, channels == 3 ? rgb.data() : all.data())) {
      why = input->geterror();
      if (why.empty()) why = "the image reader failed";
      return false;
    }
    input->close();
    if (channels != 3) {
      for (std::size_t i = 0; i < n; i++) {
        for (int c = 0; c < 3; c++) rgb[3 * i + c] = all[i * std::size_t(channels) + std::size_t(channels > 3 ? c : 0)];
      }
    }
    return true;
  }
};

}  // namespace
}  // namespace pt

extern "C" __attribute__((visibility("default"))) const pt::ImageCodec* pt_image_codec() {
  static const pt::OiioCodec codec;
  return &codec;
}
