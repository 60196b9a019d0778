// The film as a file (film_file.h): what identifies a render, the sample ranges as text,
// and the part's checksum; film_part.cpp reads a part back, film_merge.cpp adds parts up.
#include "common/app/film_file.h"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <numeric>

#include "common/app/checkpoint.h"
#include "common/app/exr_file.h"
#include "common/app/film_text.h"
#include "common/base/error.h"
#include "common/scene/environment.h"
#include "common/scene/scene.h"

namespace pt {

const char* const kFilmSumChannels[4] = {"R", "G", "B", "YY"};
const char* const kFilmHalfChannel = "Yhalf";
const char* const kFilmChecksumAttribute = "pt:checksum";

namespace film_text {

[[noreturn]] void refuse(const std::string& path, const std::string& why) {
  throw Error(kExitBadScene, "'" + path + "' " + why);
}

std::string shown(const std::string& text, std::size_t limit) {
  std::string out;
  for (unsigned char c : text) {
    if (out.size() == limit) {
      out += "...";
      break;
    }
    out += c >= 0x20 && c < 0x7f ? char(c) : '?';
  }
  return "'" + out + "'";
}

bool parse_whole(const std::string& text, std::uint64_t max, std::uint64_t& value) {
  if (text.empty() || (text.size() > 1 && text[0] == '0')) return false;
  std::uint64_t v = 0;
  for (char c : text) {
    if (c < '0' || c > '9') return false;
    const std::uint64_t digit = std::uint64_t(c - '0');
    if (v > (max - digit) / 10) return false;  // v * 10 + digit > max
    v = v * 10 + digit;
  }
  value = v;
  return true;
}

bool addressable(const SampleRange& r) {
  return r.count >= 1 && r.first < kSampleIndexLimit && r.count <= kSampleIndexLimit - r.first;
}

std::string range_text(const SampleRange& r) { return std::to_string(r.first) + ":" + std::to_string(r.count); }

}  // namespace film_text

namespace {

using film_text::refuse;
using film_text::shown;

// FNV-1a, 64 bits, byte by byte: checkpoint.cpp's bytes_hash, fed in pieces. Numbers go in
// little-endian whatever the machine.
struct Fnv {
  std::uint64_t h = 14695981039346656037ull;
  void add_byte(std::uint8_t b) { h = (h ^ b) * 1099511628211ull; }
  void add_u64(std::uint64_t v) {
    for (int k = 0; k < 8; k++) add_byte(std::uint8_t(v >> (8 * k)));
  }
  void add_text(const std::string& text) {  // its length first: "ab","c" is not "a","bc"
    add_u64(text.size());
    for (char c : text) add_byte(std::uint8_t(c));
  }
};

std::string hex64(std::uint64_t v) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", (unsigned long long)v);
  return text;
}

}  // namespace

std::string format_ranges(const std::vector<SampleRange>& ranges) {
  std::string text;
  for (const SampleRange& r : ranges) text += (text.empty() ? "" : ",") + film_text::range_text(r);
  return text;
}

std::vector<SampleRange> parse_ranges(const std::string& text, const std::string& where) {
  if (text.empty()) refuse(where, "holds no samples (its pt:samples is empty)");
  auto damaged = [&](const std::string& item, const std::string& why) {
    refuse(where, "has a damaged pt:samples " + shown(text) + ": " + (item == text ? "it" : shown(item)) + " " + why +
                      "; merge parts as a stage's --out wrote them, or render this part again");
  };
  // Digits only: no sign, space or leading zero (format_ranges writes none).
  auto digits = [](const std::string& number) {
    return !number.empty() && number.find_first_not_of("0123456789") == std::string::npos &&
           (number.size() == 1 || number[0] != '0');
  };
  std::vector<SampleRange> ranges;
  for (std::size_t at = 0;;) {
    std::size_t end = text.find(',', at);
    if (end == std::string::npos) end = text.size();
    const std::string item = text.substr(at, end - at);
    const std::size_t colon = item.find(':');
    if (colon == std::string::npos || !digits(item.substr(0, colon)) || !digits(item.substr(colon + 1))) {
      damaged(item, "is not FIRST:COUNT in whole numbers");
    }
    SampleRange r;
    if (!film_text::parse_whole(item.substr(0, colon), kSampleIndexLimit, r.first) ||
        !film_text::parse_whole(item.substr(colon + 1), kSampleIndexLimit, r.count) || (r.count > 0 && !film_text::addressable(r))) {
      damaged(item, "goes past sample index " + std::to_string(kSampleIndexLimit - 1));
    }
    if (r.count == 0) damaged(item, "holds no sample");
    if (!ranges.empty() && r.first < ranges.back().first + ranges.back().count) {
      damaged(item, "overlaps or comes before the range before it");
    }
    ranges.push_back(r);
    if (end == text.size()) break;
    at = end + 1;
  }
  return ranges;
}

std::string film_checksum(const ExrImage& image, const std::string& stage, const std::string& seed) {
  Fnv f;
  f.add_text("pt:checksum 1");  // the layout of what is hashed, should it ever change
  f.add_u64(std::uint64_t(image.width));
  f.add_u64(std::uint64_t(image.height));
  for (const std::string& field : {stage, image.attribute("pt:scene_hash"), image.attribute("pt:options"), seed,
                                   image.attribute("pt:samples"), image.attribute("pt:halves")}) {
    f.add_text(field);
  }
  // The channels in the order of their names: an .exr stores them so, whatever order they
  // were written in.
  const std::size_t n = image.channels.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return image.channels[a] < image.channels[b]; });
  for (std::size_t c : order) {
    f.add_text(image.channels[c]);
    f.add_byte(c < image.is_uint.size() && image.is_uint[c] ? 1 : 0);
  }
  const std::size_t values = std::size_t(std::max(image.width, 0)) * std::size_t(std::max(image.height, 0)) * n;
  if (image.pixels.size() != values) return "no pixels";  // matches no written checksum
  // The pixels in four lanes, byte k of every value in lane k: four chains of multiplies that
  // the processor runs side by side, about four times as fast as one. Their hashes end it.
  Fnv lanes[4];
  for (std::size_t p = 0; p < values; p += n) {
    for (std::size_t c : order) {
      const std::uint32_t v = image.pixels[p + c];
      for (int k = 0; k < 4; k++) lanes[k].add_byte(std::uint8_t(v >> (8 * k)));
    }
  }
  for (const Fnv& lane : lanes) f.add_u64(lane.h);
  return hex64(f.h);
}

FilmIdentity film_identity(const char* stage, const Scene& scene, const RenderSettings& s) {
  FilmIdentity id;
  id.stage = stage;
  id.scene_hash = hex64(scene_hash(scene));
  // The camera as the kernel sees it depends on the image's aspect: hash its bytes.
  const Camera camera = make_camera(scene, float(s.width) / float(s.height));
  const std::uint64_t h = bytes_hash(&camera, sizeof camera);
  char text[256];
  std::snprintf(text, sizeof text, "%dx%d, sky %.9g,%.9g,%.9g, rr %s, depth cap %u, sampler %s, camera %s", s.width, s.height,
                double(s.sky.x), double(s.sky.y), double(s.sky.z), s.roulette == kRouletteThroughput ? "throughput" : "fixed",
                unsigned(s.depth_cap), s.sampler == kSamplerIndependent ? "independent" : "sobol", hex64(h).c_str());
  id.options = text;
  if (scene.environment) {  // its content is in the scene's hash; here what a reader can check
    char env[160];
    std::snprintf(env, sizeof env, ", env mean luminance %.9g (strength %.9g), rotate %.9g", double(scene.environment->mean_luminance),
                  double(scene.environment->strength), double(scene.environment->rotate_degrees));
    id.options += env;
  }
  id.seed = s.seed;
  return id;
}

}  // namespace pt
