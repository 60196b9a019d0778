// The film as a file (film_file.h): what identifies a render, the sample ranges, the
// part's checksum, reading a part back from its .exr without trusting it, and adding parts
// of one render up.
#include "common/app/film_file.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <numeric>

#include "common/app/checkpoint.h"
#include "common/app/exr_file.h"
#include "common/base/error.h"
#include "common/scene/environment.h"
#include "common/scene/scene.h"

namespace pt {

const char* const kFilmSumChannels[4] = {"R", "G", "B", "YY"};
const char* const kFilmHalfChannel = "Yhalf";
const char* const kFilmChecksumAttribute = "pt:checksum";

namespace {

[[noreturn]] void refuse(const std::string& path, const std::string& why) {
  throw Error(kExitBadScene, "'" + path + "' " + why);
}

// A text from a file as an error line may show it: quoted, printable ASCII, at most `limit`
// characters (a header may hold anything, newlines too).
std::string shown(const std::string& text, std::size_t limit = 40) {
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

// A whole number as format_ranges and std::to_string write it: digits only, no sign, no
// leading zero, nothing after it, at most `max` (checked before it could overflow).
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

// A range a render can hold: not empty, and its end (first + count) at most kSampleIndexLimit,
// so that no end and no sum of one part's counts overflows.
bool addressable(const SampleRange& r) {
  return r.count >= 1 && r.first < kSampleIndexLimit && r.count <= kSampleIndexLimit - r.first;
}

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

std::string range_text(const SampleRange& r) { return std::to_string(r.first) + ":" + std::to_string(r.count); }

}  // namespace

std::string format_ranges(const std::vector<SampleRange>& ranges) {
  std::string text;
  for (const SampleRange& r : ranges) text += (text.empty() ? "" : ",") + range_text(r);
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
    if (!parse_whole(item.substr(0, colon), kSampleIndexLimit, r.first) ||
        !parse_whole(item.substr(colon + 1), kSampleIndexLimit, r.count) || (r.count > 0 && !addressable(r))) {
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

FilmPart read_film_part(const std::string& path) {
  ExrImage image;
  std::string why;
  if (!read_exr(path, image, why)) {
    refuse(path, "cannot be read as an .exr (" + why + "); give the .exr parts --out wrote");
  }
  return film_part_of(image, path);
}

namespace {

// The header's identity, strictly: the scene hash 16 hex digits, the seed a whole number
// that fits 32 bits.
FilmIdentity identity_of(const ExrImage& image, const std::string& path, std::string& seed) {
  auto text = [&](const char* name) {
    const std::string value = image.attribute(name);
    if (value.empty()) {
      refuse(path, std::string("has no ") + name +
                       ": it is not a part written by a stage's --out .exr (render the part again as .exr)");
    }
    return value;
  };
  FilmIdentity id;
  id.stage = text("pt:stage");
  id.scene_hash = text("pt:scene_hash");
  if (id.scene_hash.size() != 16 || id.scene_hash.find_first_not_of("0123456789abcdef") != std::string::npos) {
    refuse(path, "has a damaged pt:scene_hash " + shown(id.scene_hash) +
                     " (not 16 hex digits); merge parts as a stage's --out wrote them, or render this part again");
  }
  id.options = text("pt:options");
  seed = text("pt:seed");
  std::uint64_t value = 0;
  if (!parse_whole(seed, std::numeric_limits<std::uint32_t>::max(), value)) {
    refuse(path, "has a damaged pt:seed " + shown(seed) +
                     " (not a whole number from 0 to 4294967295); merge parts as a stage's --out wrote them, or "
                     "render this part again");
  }
  id.seed = std::uint32_t(value);
  return id;
}

// The sample count the header claims against the film's own numbers (film_part_of, in
// film_file.h): what a part without a checksum, or with one computed again after an edit,
// still has to pass. A pixel whose samples are alike (a light, a flat wall) needs all of
// them by Cauchy-Schwarz, so a claim of fewer is found wherever such a pixel is; Y.variance
// was computed by the writer (exr_image() in image_output.cpp) with the count it had, so a
// claim of another count is found wherever a pixel varies. Pixels whose sums are not finite
// prove nothing (pt_compare refuses them: compare.h).
void check_sample_count(const ExrImage& image, const Film& film, const std::string& path) {
  constexpr double kRounding = 1e-4;  // the kernels' float sums of up to 16 samples: about 1e-6
  const double n = double(film.spp());
  const int width = film.width(), height = film.height();
  auto refuse_pixel = [&](int x, int y, const std::string& what) {
    refuse(path, "claims " + std::to_string(film.spp()) + " samples in its pt:samples, but its pixel (" +
                     std::to_string(x) + ", " + std::to_string(y) + ") " + what +
                     ": its header does not match its film (edited or damaged); render the part again");
  };
  auto sums = [&](int x, int y, double& sum, double& squares) {
    const double* s = &film.sums()[4 * (std::size_t(y) * std::size_t(width) + std::size_t(x))];
    sum = luminance(glm::dvec3(s[0], s[1], s[2])), squares = s[3];
    return std::isfinite(sum) && std::isfinite(squares);
  };
  double sum, squares;
  for (int y = 0; y < height; y++) {
    for (int x = 0; x < width; x++) {
      if (!sums(x, y, sum, squares)) continue;
      if (squares < 0.0) refuse_pixel(x, y, "has a negative sum of squares");
      if (sum * sum > n * squares * (1.0 + kRounding)) {
        char least[32];  // (sum)^2 / (sum of squares), which may be far beyond any integer type
        std::snprintf(least, sizeof least, "%.15g", std::floor(sum * sum / squares));
        refuse_pixel(x, y, std::string("holds at least ") + least);
      }
    }
  }
  const int variance = image.channel("Y.variance");
  if (variance < 0 || image.is_uint[std::size_t(variance)]) return;
  for (int y = 0; y < height; y++) {
    for (int x = 0; x < width; x++) {
      if (!sums(x, y, sum, squares)) continue;
      const std::size_t p = std::size_t(y) * std::size_t(width) + std::size_t(x);
      float stored;
      std::memcpy(&stored, &image.pixels[p * image.channels.size() + std::size_t(variance)], sizeof stored);
      const float expected = film.spp() >= 2 ? float(film.sample_variance(x, y) / n) : 0.0f;
      // Float rounding, and the cancellation in the variance of a pixel whose samples are alike.
      const double slack = 1e-3 * std::max(std::fabs(double(stored)), std::fabs(double(expected))) +
                           (n >= 2.0 ? 1e-9 * squares / (n * (n - 1.0)) : 0.0);
      if (stored != expected && !(std::fabs(double(stored) - double(expected)) <= slack)) {
        refuse_pixel(x, y, "has the variance (Y.variance) of another count");
      }
    }
  }
}

}  // namespace

FilmPart film_part_of(const ExrImage& image, const std::string& path) {
  FilmPart part;
  part.path = path;
  std::string seed;
  part.id = identity_of(image, path, seed);
  part.scene = image.attribute("pt:scene");
  part.backend = image.attribute("pt:backend");
  const std::string samples = image.attribute("pt:samples");
  if (samples.empty()) {
    refuse(path, "has no pt:samples: it is not a part written by a stage's --out .exr (render the part again as .exr)");
  }
  part.ranges = parse_ranges(samples, path);
  std::uint64_t spp = 0;
  for (const SampleRange& r : part.ranges) spp += r.count;  // ascending, below kSampleIndexLimit: no overflow
  // The checksum, where the part has one (parts written before it existed are read, and noted).
  const std::string checksum = image.attribute(kFilmChecksumAttribute);
  part.checksummed = !checksum.empty();
  if (part.checksummed && checksum != film_checksum(image, part.id.stage, seed)) {
    refuse(path, "is damaged or was edited: its pt:checksum does not match its header and pixels; render the part "
                 "again");
  }
  // The sums, from the 32-bit halves of each double (a channel of another type or a
  // missing one: not a part).
  int index[8];
  for (int k = 0; k < 4; k++) {
    for (int half = 0; half < 2; half++) {
      const std::string name = std::string("film.") + kFilmSumChannels[k] + (half ? ".lo" : ".hi");
      const int c = image.channel(name);
      if (c < 0 || !image.is_uint[std::size_t(c)]) {
        refuse(path, "has no channel " + name + " of 32-bit integers: it is not a part written by a stage's --out .exr");
      }
      index[2 * k + half] = c;
    }
  }
  const std::size_t pixels = std::size_t(image.width) * std::size_t(image.height), n = image.channels.size();
  std::vector<double> sums(4 * pixels);
  for (std::size_t p = 0; p < pixels; p++) {
    const std::uint32_t* v = &image.pixels[p * n];
    for (int k = 0; k < 4; k++) sums[4 * p + std::size_t(k)] = join_double(v[index[2 * k]], v[index[2 * k + 1]]);
  }
  part.film = Film(image.width, image.height);
  part.film.restore(spp, std::move(sums));
  check_sample_count(image, part.film, path);
  // The first half's luminance sums, where the render knew its halves (optional: without them,
  // or with an attribute that does not name the first half of this part's one range, the film
  // simply does not know them).
  const int hi = image.channel(std::string("film.") + kFilmHalfChannel + ".hi");
  const int lo = image.channel(std::string("film.") + kFilmHalfChannel + ".lo");
  const std::string halves = image.attribute("pt:halves");
  if (hi >= 0 && lo >= 0 && image.is_uint[std::size_t(hi)] && image.is_uint[std::size_t(lo)] &&
      part.ranges.size() == 1 && halves == format_ranges({{part.ranges.front().first, spp / 2}})) {
    std::vector<double> luminance(pixels);
    for (std::size_t p = 0; p < pixels; p++) luminance[p] = join_double(image.pixels[p * n + hi], image.pixels[p * n + lo]);
    part.film.restore_halves(spp / 2, std::move(luminance));
  }
  part.kept_halves = hi >= 0 && lo >= 0;
  return part;
}

std::string unchecked_note(const FilmPart& part) {
  if (part.checksummed) return "";
  return "'" + part.path + "' has no pt:checksum (written before parts carried one): damage to it cannot be found, only "
         "a header that disagrees with its film's sums; render it again to have it checked";
}

FilmPart merge_film_parts(std::vector<FilmPart> parts, std::vector<std::string>& notes) {
  if (parts.empty()) throw Error(kExitBadOption, "no parts to merge");
  const FilmPart& ref = parts.front();
  auto differs = [&](const FilmPart& p, const char* field, const std::string& mine, const std::string& theirs) {
    if (mine != theirs) {
      refuse(p.path, std::string("is a part of another render: its ") + field + " is " + shown(mine, 200) + ", '" +
                         ref.path + "' has " + shown(theirs, 200) + "; merge only parts of one render");
    }
  };
  for (const FilmPart& p : parts) {
    // Ranges a render can hold, adding up to its film's count (film_part_of reads no other;
    // a part made in code is held to it too): no end or sum below can overflow.
    std::uint64_t count = 0;
    for (const SampleRange& r : p.ranges) {
      if (!addressable(r)) {
        refuse(p.path, "holds a sample range " + range_text(r) + " that is empty or goes past sample index " +
                           std::to_string(kSampleIndexLimit - 1) + "; render the part again");
      }
      count += r.count;
    }
    if (p.ranges.empty() || count != p.film.spp()) {
      refuse(p.path, "holds " + std::to_string(p.film.spp()) + " samples, but its sample ranges '" +
                         format_ranges(p.ranges) + "' hold " + std::to_string(count) + "; render the part again");
    }
    if (!p.checksummed) notes.push_back(unchecked_note(p));
    differs(p, "stage", p.id.stage, ref.id.stage);
    differs(p, "scene (content hash)", p.id.scene_hash, ref.id.scene_hash);
    differs(p, "options", p.id.options, ref.id.options);
    differs(p, "seed", std::to_string(p.id.seed), std::to_string(ref.id.seed));
    differs(p, "size", std::to_string(p.film.width()) + "x" + std::to_string(p.film.height()),
            std::to_string(ref.film.width()) + "x" + std::to_string(ref.film.height()));
    if (p.backend != ref.backend) {
      notes.push_back("'" + p.path + "' was rendered on " + p.backend + ", '" + ref.path + "' on " + ref.backend +
                      ": the merge equals one run to float rounding, not bit for bit");
    }
  }
  // Every range with the part that holds it, in sample order: no sample may be in two parts.
  struct Held {
    SampleRange range;
    std::size_t part;
  };
  std::vector<Held> held;
  for (std::size_t i = 0; i < parts.size(); i++) {
    for (const SampleRange& r : parts[i].ranges) held.push_back({r, i});
  }
  std::sort(held.begin(), held.end(), [](const Held& a, const Held& b) { return a.range.first < b.range.first; });
  std::vector<SampleRange> merged;
  for (std::size_t i = 0; i < held.size(); i++) {
    const SampleRange& r = held[i].range;
    if (i > 0) {
      const Held& before = held[i - 1];
      const std::uint64_t end = before.range.first + before.range.count;
      if (r.first < end) {
        refuse(parts[held[i].part].path, "holds samples " + range_text(r) + ", which overlap the samples " +
                                             range_text(before.range) + " of '" + parts[before.part].path +
                                             "'; merge parts with separate --samples ranges");
      }
      if (r.first > end) {
        notes.push_back("samples " + range_text({end, r.first - end}) +
                        " are in no part: the merge is an image of the samples it has");
      }
    }
    if (!merged.empty() && merged.back().first + merged.back().count == r.first) {
      merged.back().count += r.count;
    } else {
      merged.push_back(r);
    }
  }
  // The sums in the order of the parts' first samples, as one run adds its passes.
  std::vector<std::size_t> order(parts.size());
  for (std::size_t i = 0; i < order.size(); i++) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return parts[a].ranges.front().first < parts[b].ranges.front().first;
  });
  // Under the default sampler, parts that follow one another without a gap keep the two
  // halves of an aligned block known, for the per-pixel error (film.h, track_halves).
  bool follow = merged.size() == 1 && ref.id.options.find("sampler sobol") != std::string::npos;
  for (const FilmPart& p : parts) follow = follow && p.ranges.size() == 1;
  FilmPart out = parts[order[0]];
  for (const FilmPart& p : parts) out.kept_halves = out.kept_halves || p.kept_halves;
  // (One part keeps the halves it was read with.)
  if (follow && parts.size() > 1) out.film.track_halves(out.ranges.front().first);
  for (std::size_t k = 1; k < order.size(); k++) out.film.merge(parts[order[k]].film, follow);
  out.ranges = merged;
  out.path.clear();
  return out;
}

}  // namespace pt
