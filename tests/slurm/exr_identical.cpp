// pt_exr_identical A.exr B.exr: whether two EXR images hold the same pixels bit for bit, in
// every channel, each read in its own type (float, or the uint halves of the film's doubles;
// the Slurm and GNU parallel tests compare a merged render with a one-run render through
// it). Exit 0 identical, 1 different (the first difference and the count on stdout), 2
// unreadable, or of another size, channel list or channel type.
#include <OpenImageIO/imageio.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace {

struct Image {
  int width = 0, height = 0;
  std::vector<std::string> channels;
  std::vector<OIIO::TypeDesc> types;
  std::vector<std::vector<unsigned char>> planes;  // each channel's pixels, in its own type
};

bool read(const char* path, Image& image) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    std::fprintf(stderr, "pt_exr_identical: cannot read %s: %s\n", path, OIIO::geterror().c_str());
    return false;
  }
  const OIIO::ImageSpec& spec = in->spec();
  image.width = spec.width;
  image.height = spec.height;
  image.channels = spec.channelnames;
  for (int c = 0; c < spec.nchannels; ++c) {
    const OIIO::TypeDesc type = spec.channelformat(c);
    image.types.push_back(type);
    image.planes.emplace_back(std::size_t(spec.width) * spec.height * type.size());
    if (!in->read_image(0, 0, c, c + 1, type, image.planes.back().data())) {
      std::fprintf(stderr, "pt_exr_identical: cannot read channel %s of %s: %s\n", spec.channelnames[c].c_str(), path,
                   in->geterror().c_str());
      return false;
    }
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: pt_exr_identical A.exr B.exr\n");
    return 2;
  }
  Image a, b;
  if (!read(argv[1], a) || !read(argv[2], b)) return 2;
  if (a.width != b.width || a.height != b.height) {
    std::fprintf(stderr, "pt_exr_identical: %s is %dx%d, %s is %dx%d\n", argv[1], a.width, a.height,
                 argv[2], b.width, b.height);
    return 2;
  }
  // The channels both images have, by name (B's index of each of A's).
  std::vector<std::pair<std::size_t, std::size_t>> common;
  for (std::size_t i = 0; i < a.channels.size(); ++i)
    for (std::size_t j = 0; j < b.channels.size(); ++j)
      if (a.channels[i] == b.channels[j]) common.emplace_back(i, j);
  if (common.empty() || common.size() != a.channels.size() || common.size() != b.channels.size()) {
    std::string list_a, list_b;
    for (const auto& c : a.channels) list_a += " " + c;
    for (const auto& c : b.channels) list_b += " " + c;
    std::fprintf(stderr, "pt_exr_identical: other channels: %s has%s, %s has%s\n", argv[1], list_a.c_str(),
                 argv[2], list_b.c_str());
    return 2;
  }
  std::uint64_t differing = 0;
  for (const auto& [i, j] : common) {
    if (a.types[i] != b.types[j]) {
      std::fprintf(stderr, "pt_exr_identical: channel %s is %s in %s and %s in %s\n", a.channels[i].c_str(),
                   a.types[i].c_str(), argv[1], b.types[j].c_str(), argv[2]);
      return 2;
    }
    const std::size_t size = a.types[i].size();
    for (std::size_t p = 0; p < std::size_t(a.width) * a.height; ++p) {
      const unsigned char* va = a.planes[i].data() + p * size;
      const unsigned char* vb = b.planes[j].data() + p * size;
      if (std::memcmp(va, vb, size) == 0) continue;
      if (differing++ == 0) {
        std::printf("first difference: pixel %zu,%zu channel %s (%s):", p % a.width, p / a.width,
                    a.channels[i].c_str(), a.types[i].c_str());
        if (a.types[i] == OIIO::TypeDesc::FLOAT) {
          float fa, fb;
          std::memcpy(&fa, va, sizeof fa);
          std::memcpy(&fb, vb, sizeof fb);
          std::printf(" %.9g and %.9g\n", double(fa), double(fb));
        } else if (a.types[i] == OIIO::TypeDesc::UINT) {
          std::uint32_t ua, ub;
          std::memcpy(&ua, va, sizeof ua);
          std::memcpy(&ub, vb, sizeof ub);
          std::printf(" %#010x and %#010x\n", unsigned(ua), unsigned(ub));
        } else {
          std::printf(" the bytes differ\n");
        }
      }
    }
  }
  if (differing) {
    std::printf("%llu values differ\n", (unsigned long long)differing);
    return 1;
  }
  std::printf("identical: %dx%d, %zu channels\n", a.width, a.height, a.channels.size());
  return 0;
}
