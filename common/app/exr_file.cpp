// .exr files through OpenEXR (see exr_file.h).
#include "common/app/exr_file.h"

#include <algorithm>
#include <exception>
#include <new>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfIO.h>
#include <ImfStringAttribute.h>

#include "common/app/replace_file.h"
#include "common/base/error.h"

namespace pt {
namespace {

// OpenEXR's exception texts can run over several lines: the first one.
std::string first_line(const char* what) {
  std::string s = what ? what : "";
  s = s.substr(0, s.find('\n'));
  return s.empty() ? "no reason given" : s;
}

// Larger than any image a stage writes (--width and --height stop at 65,536), small enough
// that a damaged header cannot ask for terabytes.
constexpr long kMaxSide = 65536;
constexpr std::size_t kMaxChannels = 64;

// An OpenEXR output stream into memory (OpenEXR seeks back to write its line offsets).
class MemoryStream final : public Imf::OStream {
 public:
  explicit MemoryStream(std::vector<char>& bytes) : Imf::OStream("memory"), bytes_(bytes) {}
  void write(const char c[], int n) override {
    if (position_ + std::size_t(n) > bytes_.size()) bytes_.resize(position_ + std::size_t(n));
    std::copy(c, c + n, bytes_.begin() + std::ptrdiff_t(position_));
    position_ += std::size_t(n);
  }
  uint64_t tellp() override { return position_; }
  void seekp(uint64_t pos) override { position_ = std::size_t(pos); }

 private:
  std::vector<char>& bytes_;
  std::size_t position_ = 0;
};

}  // namespace

int ExrImage::channel(const std::string& name) const {
  auto it = std::find(channels.begin(), channels.end(), name);
  return it == channels.end() ? -1 : int(it - channels.begin());
}

std::string ExrImage::attribute(const std::string& name) const {
  for (const auto& [key, value] : text) {
    if (key == name) return value;
  }
  return "";
}

void ExrImage::set_attribute(const std::string& name, const std::string& value) {
  auto it = std::find_if(text.begin(), text.end(), [&](const auto& kv) { return kv.first == name; });
  if (it == text.end()) {
    if (!value.empty()) text.emplace_back(name, value);
  } else if (value.empty()) {
    text.erase(it);
  } else {
    it->second = value;
  }
}

bool encode_exr(const ExrImage& image, std::vector<char>& bytes, std::string& why) {
  bytes.clear();
  try {
    Imf::Header header(image.width, image.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    for (const auto& [key, value] : image.text) header.insert(key, Imf::StringAttribute(value));
    const std::size_t n = image.channels.size();
    const std::size_t x_stride = n * sizeof(std::uint32_t), y_stride = x_stride * std::size_t(image.width);
    Imf::FrameBuffer frame;
    for (std::size_t c = 0; c < n; c++) {
      const Imf::PixelType type = image.is_uint[c] ? Imf::UINT : Imf::FLOAT;
      header.channels().insert(image.channels[c], Imf::Channel(type));
      char* base = const_cast<char*>(reinterpret_cast<const char*>(image.pixels.data() + c));
      frame.insert(image.channels[c], Imf::Slice(type, base, x_stride, y_stride));
    }
    // Room for the channels uncompressed (a chunk that ZIP does not shrink is stored as it
    // is) and the header: the bytes never grow by doubling (common/render/memory.cpp).
    bytes.reserve(std::size_t(image.height) * y_stride + std::size_t(image.height) * 16 + (std::size_t(1) << 20));
    MemoryStream stream(bytes);
    {
      Imf::OutputFile file(stream, header);
      file.setFrameBuffer(frame);
      file.writePixels(image.height);
    }  // the file's destructor writes its line offsets
    return true;
  } catch (const std::bad_alloc&) {
    throw;  // not a write error: run_guarded says out of memory, exit 2 (common/render/memory.h)
  } catch (const std::exception& e) {
    why = first_line(e.what());
    return false;
  }
}

bool write_exr(const std::string& path, const ExrImage& image, std::string& why) {
  std::vector<char> bytes;
  if (!encode_exr(image, bytes, why)) return false;
  try {
    replace_file(path, {{bytes.data(), bytes.size()}}, "free some space or choose another path");
    return true;
  } catch (const Error& e) {
    why = e.what();
    return false;
  }
}

bool read_exr(const std::string& path, ExrImage& image, std::string& why) {
  try {
    Imf::InputFile file(path.c_str());
    const Imf::Header& header = file.header();
    const Imath::Box2i window = header.dataWindow();
    if (window.min.x != 0 || window.min.y != 0) {
      why = "its data window does not start at pixel 0, 0";
      return false;
    }
    const long width = long(window.max.x) + 1, height = long(window.max.y) + 1;
    image = ExrImage{};
    for (auto c = header.channels().begin(); c != header.channels().end(); ++c) {
      if (c.channel().xSampling != 1 || c.channel().ySampling != 1) {
        why = std::string("its channel ") + c.name() + " is subsampled";
        return false;
      }
      image.channels.push_back(c.name());
      image.is_uint.push_back(c.channel().type == Imf::UINT);
    }
    if (width < 1 || height < 1 || width > kMaxSide || height > kMaxSide || image.channels.size() > kMaxChannels) {
      why = "its size (" + std::to_string(width) + " x " + std::to_string(height) + ", " +
            std::to_string(image.channels.size()) + " channels) is not that of a render";
      return false;
    }
    image.width = int(width), image.height = int(height);
    for (auto a = header.begin(); a != header.end(); ++a) {
      if (auto* s = dynamic_cast<const Imf::StringAttribute*>(&a.attribute())) image.text.emplace_back(a.name(), s->value());
    }
    const std::size_t n = image.channels.size();
    image.pixels.assign(std::size_t(width) * std::size_t(height) * n, 0u);
    const std::size_t x_stride = n * sizeof(std::uint32_t), y_stride = x_stride * std::size_t(width);
    Imf::FrameBuffer frame;
    for (std::size_t c = 0; c < n; c++) {
      const Imf::PixelType type = image.is_uint[c] ? Imf::UINT : Imf::FLOAT;
      frame.insert(image.channels[c], Imf::Slice(type, reinterpret_cast<char*>(image.pixels.data() + c), x_stride, y_stride));
    }
    file.setFrameBuffer(frame);
    file.readPixels(0, int(height) - 1);
    return true;
  } catch (const std::bad_alloc&) {
    throw;  // not a damaged file: run_guarded says out of memory, exit 2
  } catch (const std::exception& e) {
    why = first_line(e.what());
    return false;
  }
}

}  // namespace pt
