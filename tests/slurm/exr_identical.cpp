// pt_exr_identical A.exr B.exr: whether two EXR images hold the same pixels bit for bit, in
// every channel both have (the Slurm and GNU parallel tests compare a merged render with a
// one-run render through it). Exit 0 identical, 1 different (the first difference and the
// count on stdout), 2 unreadable or of another size or channel list.
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
  std::vector<float> pixels;
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
  image.pixels.resize(std::size_t(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data())) {
    std::fprintf(stderr, "pt_exr_identical: cannot read the pixels of %s: %s\n", path, in->geterror().c_str());
    return false;
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
  const std::size_t na = a.channels.size(), nb = b.channels.size();
  std::uint64_t differing = 0;
  for (std::size_t p = 0; p < std::size_t(a.width) * a.height; ++p) {
    for (const auto& [i, j] : common) {
      const float va = a.pixels[p * na + i], vb = b.pixels[p * nb + j];
      if (std::memcmp(&va, &vb, sizeof va) == 0) continue;
      if (differing++ == 0)
        std::printf("first difference: pixel %zu,%zu channel %s: %.9g and %.9g\n", p % a.width, p / a.width,
                    a.channels[i].c_str(), double(va), double(vb));
    }
  }
  if (differing) {
    std::printf("%llu values differ\n", (unsigned long long)differing);
    return 1;
  }
  std::printf("identical: %dx%d, %zu channels\n", a.width, a.height, na);
  return 0;
}
