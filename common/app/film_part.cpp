// Reading a part of a render back from its .exr (film_file.h, read_film_part and
// film_part_of) without trusting it: the header's identity and numbers read strictly, the
// checksum, and the sample count it claims held against the film's own sums.
// Not in the article: the machinery of parts and merges (the contract (README.md), "Parts,
// merging and comparing").
#include "common/app/film_file.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "common/app/exr_file.h"
#include "common/app/film_text.h"
#include "common/base/error.h"

namespace pt {

namespace {

using film_text::refuse;
using film_text::shown;

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
  if (!film_text::parse_whole(seed, std::numeric_limits<std::uint32_t>::max(), value)) {
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

FilmPart read_film_part(const std::string& path) {
  ExrImage image;
  std::string why;
  if (!read_exr(path, image, why)) {
    refuse(path, "cannot be read as an .exr (" + why + "); give the .exr parts --out wrote");
  }
  return film_part_of(image, path);
}

std::string unchecked_note(const FilmPart& part) {
  if (part.checksummed) return "";
  return "'" + part.path + "' has no pt:checksum (written before parts carried one): damage to it cannot be found, only "
         "a header that disagrees with its film's sums; render it again to have it checked";
}

}  // namespace pt
