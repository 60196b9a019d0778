// An 8-bit RGBA PNG written in memory, for tests that embed their own textures in a glTF file
// (tests/support/gltf_textured.h image_texture): stored (uncompressed) deflate blocks, every
// texel exactly as given. OpenImageIO reaches pt_gpu_tests only through the pt_openimageio
// module, whose encoder writes RGB; alpha masks need RGBA. Not part of the article: test machinery.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

namespace pt::test {

namespace png_detail {

inline std::uint32_t crc32(const unsigned char* data, std::size_t size, std::uint32_t crc = 0xffffffffu) {
  for (std::size_t i = 0; i < size; i++) {
    crc ^= data[i];
    for (int k = 0; k < 8; k++) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return crc;
}

inline void put32(std::vector<unsigned char>& out, std::uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back((unsigned char)(v >> s));
}

inline void chunk(std::vector<unsigned char>& out, const char* type, const std::vector<unsigned char>& data) {
  put32(out, std::uint32_t(data.size()));
  std::vector<unsigned char> body(type, type + 4);
  body.insert(body.end(), data.begin(), data.end());
  out.insert(out.end(), body.begin(), body.end());
  put32(out, crc32(body.data(), body.size()) ^ 0xffffffffu);
}

}  // namespace png_detail

// A width x height RGBA image, texels packed R | G << 8 | B << 16 | A << 24 (texels.h rgba),
// rows from the top.
inline std::vector<unsigned char> png_rgba(std::uint32_t width, std::uint32_t height,
                                           const std::vector<std::uint32_t>& texels) {
  using namespace png_detail;
  std::vector<unsigned char> raw;  // each row: filter 0, then RGBA
  for (std::uint32_t y = 0; y < height; y++) {
    raw.push_back(0);
    for (std::uint32_t x = 0; x < width; x++) {
      std::uint32_t v = texels[std::size_t(y) * width + x];
      for (int c = 0; c < 4; c++) raw.push_back((unsigned char)(v >> (8 * c)));
    }
  }
  std::vector<unsigned char> z = {0x78, 0x01};  // zlib header, stored blocks of at most 65535 bytes
  std::uint32_t a = 1, b = 0;                   // Adler-32
  for (std::size_t at = 0; at < raw.size() || at == 0; at += 65535) {
    std::size_t n = std::min<std::size_t>(65535, raw.size() - at);
    z.push_back(at + n >= raw.size() ? 1 : 0);
    z.push_back((unsigned char)(n & 255)), z.push_back((unsigned char)(n >> 8));
    z.push_back((unsigned char)(~n & 255)), z.push_back((unsigned char)((~n >> 8) & 255));
    for (std::size_t i = at; i < at + n; i++) {
      z.push_back(raw[i]);
      a = (a + raw[i]) % 65521u, b = (b + a) % 65521u;
    }
    if (raw.empty()) break;
  }
  put32(z, b << 16 | a);
  std::vector<unsigned char> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  std::vector<unsigned char> header;
  put32(header, width), put32(header, height);
  for (unsigned char v : {8, 6, 0, 0, 0}) header.push_back(v);  // 8 bits, RGBA, deflate, no filter, no interlace
  chunk(png, "IHDR", header);
  chunk(png, "IDAT", z);
  chunk(png, "IEND", {});
  return png;
}

}  // namespace pt::test
