// pt_exr_identical [--tolerance NAME=REL]... A.exr B.exr: whether two EXR images hold the
// same pixels bit for bit, in every channel, each read in its own type (float, or the uint
// halves of the film's doubles; the Slurm and GNU parallel tests compare a merged render with
// a one-run render through it). --tolerance lets the float channel NAME, or the double whose
// halves are NAME.hi and NAME.lo, differ by REL relative (pt_merge's squared-luminance sums
// may differ from the one run's in their last bits: docs/film.md). Exit 0 identical (within
// the tolerances), 1 different (the first difference and the count on stdout), 2 unreadable,
// or of another size, channel list or channel type.
#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
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
  std::map<std::string, double> tolerance;  // channel (or double) name -> relative tolerance
  int arg = 1;
  for (; arg + 1 < argc && std::strcmp(argv[arg], "--tolerance") == 0; arg += 2) {
    const std::string spec = argv[arg + 1];
    const auto eq = spec.find('=');
    char* end = nullptr;
    const double rel = eq == std::string::npos ? -1.0 : std::strtod(spec.c_str() + eq + 1, &end);
    if (eq == std::string::npos || !(rel >= 0.0) || *end != '\0') {
      std::fprintf(stderr, "pt_exr_identical: --tolerance wants NAME=REL, not '%s'\n", spec.c_str());
      return 2;
    }
    tolerance[spec.substr(0, eq)] = rel;
  }
  if (argc - arg != 2) {
    std::fprintf(stderr, "usage: pt_exr_identical [--tolerance NAME=REL]... A.exr B.exr\n");
    return 2;
  }
  argv += arg - 1;
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
  const std::size_t pixels = std::size_t(a.width) * a.height;
  auto channel = [](const Image& image, const std::string& name) {
    for (std::size_t c = 0; c < image.channels.size(); ++c)
      if (image.channels[c] == name) return int(c);
    return -1;
  };
  // The channels with a tolerance: compared as values, and left out of the bitwise check.
  std::vector<std::string> loose;
  for (const auto& [name, rel] : tolerance) {
    const int fa = channel(a, name), fb = channel(b, name);
    const int ha = channel(a, name + ".hi"), la = channel(a, name + ".lo");
    const int hb = channel(b, name + ".hi"), lb = channel(b, name + ".lo");
    const bool is_float = fa >= 0 && fb >= 0 && a.types[fa] == OIIO::TypeDesc::FLOAT;
    const bool is_double = ha >= 0 && la >= 0 && hb >= 0 && lb >= 0 && a.types[ha] == OIIO::TypeDesc::UINT;
    if (!is_float && !is_double) {
      std::fprintf(stderr, "pt_exr_identical: --tolerance %s: no float channel %s nor uint halves %s.hi, %s.lo in both\n",
                   name.c_str(), name.c_str(), name.c_str(), name.c_str());
      return 2;
    }
    auto value = [&](const Image& image, int f, int h, int l, std::size_t p) {
      if (is_float) {
        float v;
        std::memcpy(&v, image.planes[f].data() + p * 4, 4);
        return double(v);
      }
      std::uint32_t hi, lo;
      std::memcpy(&hi, image.planes[h].data() + p * 4, 4);
      std::memcpy(&lo, image.planes[l].data() + p * 4, 4);
      const std::uint64_t bits = (std::uint64_t(hi) << 32) | lo;
      double v;
      std::memcpy(&v, &bits, 8);
      return v;
    };
    double worst = 0.0;
    for (std::size_t p = 0; p < pixels; ++p) {
      const double va = value(a, fa, ha, la, p), vb = value(b, fb, hb, lb, p);
      if (va == vb) continue;
      const double diff = std::fabs(va - vb) / std::fmax(std::fabs(va), std::fabs(vb));
      worst = std::fmax(worst, diff);
      if (diff > rel && differing++ == 0)
        std::printf("first difference: pixel %zu,%zu %s: %.17g and %.17g (relative %.3g, allowed %.3g)\n",
                    p % a.width, p / a.width, name.c_str(), va, vb, diff, rel);
    }
    std::printf("%s: largest relative difference %.3g (allowed %.3g)\n", name.c_str(), worst, rel);
    if (is_float) {
      loose.push_back(name);
    } else {
      loose.push_back(name + ".hi");
      loose.push_back(name + ".lo");
    }
  }
  for (const auto& [i, j] : common) {
    bool skip = false;
    for (const auto& name : loose) skip = skip || a.channels[i] == name;
    if (skip) continue;
    if (a.types[i] != b.types[j]) {
      std::fprintf(stderr, "pt_exr_identical: channel %s is %s in %s and %s in %s\n", a.channels[i].c_str(),
                   a.types[i].c_str(), argv[1], b.types[j].c_str(), argv[2]);
      return 2;
    }
    const std::size_t size = a.types[i].size();
    for (std::size_t p = 0; p < pixels; ++p) {
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
  std::printf("identical: %dx%d, %zu channels%s\n", a.width, a.height, a.channels.size(),
              loose.empty() ? "" : " (some within their tolerance)");
  return 0;
}
