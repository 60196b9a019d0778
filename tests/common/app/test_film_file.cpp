// Parts of one render and their merge (common/app/film_file.h, the stages' --samples
// FIRST:COUNT and pt_merge): any split of the samples 0 ... N-1 into ranges, rendered
// apart, written as .exr parts, read back and merged, is the one-run image: bit for bit
// when the ranges split at the pass schedule's ends (its variance sums to double rounding),
// to float rounding otherwise. A merge can be merged again, and knows the halves of its
// samples. What a merge refuses: test_film_part_refusals.cpp.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "common/app/film_file.h"
#include "common/app/image_output.h"
#include "common/base/error.h"
#include "common/scene/scene_loading.h"
#include "stage3_importance/kernels.h"
#include "stage4_direct_indirect/kernels.h"
#include "tests/support/film_parts.h"
#include "tests/support/test_render.h"

namespace fs = std::filesystem;
using namespace pt;
using namespace pt::test;

namespace {

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

// How many pixels' sums differ in any bit: the RGB sums (k < 3), or the squared-luminance sums.
int pixels_differing(const Film& a, const Film& b, bool rgb) {
  int n = 0;
  for (std::size_t p = 0; p < a.sums().size() / 4; p++) {
    bool same = true;
    for (std::size_t k = rgb ? 0 : 3; k < (rgb ? 3u : 4u); k++) same = same && a.sums()[4 * p + k] == b.sums()[4 * p + k];
    n += !same;
  }
  return n;
}

// Largest relative difference of the squared-luminance sums over pixels.
double largest_yy_difference(const Film& a, const Film& b) {
  double worst = 0.0;
  for (std::size_t p = 3; p < a.sums().size(); p += 4) {
    worst = std::max(worst, std::abs(a.sums()[p] - b.sums()[p]) / std::max(1e-300, std::abs(a.sums()[p])));
  }
  return worst;
}

// Largest relative difference of the mean radiance over pixels and channels.
double largest_difference(const Film& a, const Film& b) {
  double worst = 0.0;
  for (int y = 0; y < a.height(); y++) {
    for (int x = 0; x < a.width(); x++) {
      glm::dvec3 u = a.mean(x, y), v = b.mean(x, y);
      for (int c = 0; c < 3; c++) worst = std::max(worst, std::abs(u[c] - v[c]) / std::max(1e-30, std::abs(u[c])));
    }
  }
  return worst;
}

}  // namespace

TEST_CASE("film parts: any split of the samples merges into the one-run image, bit for bit at pass ends",
          "[stage4][film][parts]") {
  const Scene scene = make_builtin_scene("cornell");
  RenderSettings s = settings(20, 16, 80, 11);
  s.roulette = kRouletteThroughput;
  std::unique_ptr<Backend> backend = make_backend("cpu", stage4::kernels());
  const RenderResult one = render(*backend, scene, s);
  std::mt19937 rng(5);
  for (int trial = 0; trial < 8; trial++) {
    const bool at_pass_ends = trial % 2 == 0;
    const int parts = 1 + trial;  // 1 to 8
    // Cut points: pass ends (1, 2, 4, 8, 16, 32, 48, 64) or any sample index.
    std::vector<std::uint64_t> cuts = {0, s.spp};
    const std::vector<std::uint64_t> ends = {1, 2, 4, 8, 16, 32, 48, 64};
    while (int(cuts.size()) < parts + 1) {
      std::uint64_t c = at_pass_ends ? ends[rng() % ends.size()] : 1 + rng() % (s.spp - 1);
      if (std::find(cuts.begin(), cuts.end(), c) == cuts.end()) cuts.push_back(c);
    }
    std::sort(cuts.begin(), cuts.end());
    std::vector<FilmPart> read;
    for (std::size_t i = 0; i + 1 < cuts.size(); i++) {
      const std::string name = "t" + std::to_string(trial) + "_" + std::to_string(i) + ".exr";
      read.push_back(read_film_part(render_part(stage4::kernels(), scene, s, cuts[i], cuts[i + 1] - cuts[i], name)));
    }
    std::shuffle(read.begin(), read.end(), rng);  // the order given to the merge does not matter
    std::vector<std::string> notes;
    const FilmPart merged = merge_film_parts(read, notes);
    INFO("trial " << trial << ", " << parts << " parts, " << (at_pass_ends ? "at pass ends" : "anywhere"));
    CHECK(notes.empty());
    CHECK(merged.film.spp() == s.spp);
    CHECK(format_ranges(merged.ranges) == "0:80");
    if (at_pass_ends) {
      // The image bit for bit. The squared-luminance sums add squares of floats (48-bit
      // values) in double, whose rounding depends on the grouping: equal to a few ulps.
      CHECK(pixels_differing(merged.film, one.film, true) == 0);
      CHECK(largest_yy_difference(merged.film, one.film) <= 1e-14);
    } else {
      CHECK(largest_difference(merged.film, one.film) <= 1e-5);  // float rounding of the pass sums
    }
  }
}

TEST_CASE("film parts: a merge is a part: merged again it gives the same image", "[stage3][film][parts]") {
  const Scene scene = make_builtin_scene("furnace");
  RenderSettings s = settings(8, 8, 64, 12);
  s.roulette = kRouletteThroughput;
  const std::string a = render_part(stage3::kernels(), scene, s, 0, 16, "mm_a.exr");
  const std::string b = render_part(stage3::kernels(), scene, s, 16, 16, "mm_b.exr");
  const std::string c = render_part(stage3::kernels(), scene, s, 32, 32, "mm_c.exr");
  std::vector<std::string> notes;
  const FilmPart all = merge_film_parts({read_film_part(a), read_film_part(b), read_film_part(c)}, notes);
  FilmPart ab = merge_film_parts({read_film_part(a), read_film_part(b)}, notes);
  ImageMetadata meta;
  meta.stage = ab.id.stage, meta.backend = ab.backend, meta.film = &ab.film, meta.identity = ab.id, meta.ranges = ab.ranges;
  meta.seed = ab.id.seed;  // as pt_merge writes it
  const std::string ab_path = scratch("mm_ab.exr").string();
  OutputFile(ab_path).write(ab.film.mean_rgb(), 8, 8, meta);
  const FilmPart again = merge_film_parts({read_film_part(c), read_film_part(ab_path)}, notes);
  CHECK(notes.empty());
  CHECK(same_bits(again.film.sums(), all.film.sums()));
  CHECK(format_ranges(again.ranges) == "0:64");
}

// Under the default sampler a render prints the error from the two halves of its samples
// (common/render/film.h, track_halves); parts that follow one another keep those halves.
TEST_CASE("film parts: a merge of parts that follow one another knows the halves of its samples, as one run does",
          "[stage3][film][parts]") {
  const Scene scene = make_builtin_scene("furnace");
  RenderSettings s = settings(8, 8, 64, 13);
  s.roulette = kRouletteThroughput;
  REQUIRE(s.sampler == kSamplerSobol);
  std::unique_ptr<Backend> backend = make_backend("cpu", stage3::kernels());
  const RenderResult one = render(*backend, scene, s);
  REQUIRE(one.film.has_halves());
  const std::string a = render_part(stage3::kernels(), scene, s, 0, 16, "h_a.exr");
  const std::string b = render_part(stage3::kernels(), scene, s, 16, 16, "h_b.exr");
  const std::string c = render_part(stage3::kernels(), scene, s, 32, 32, "h_c.exr");
  std::vector<std::string> notes;
  const FilmPart all = merge_film_parts({read_film_part(c), read_film_part(a), read_film_part(b)}, notes);
  CHECK(all.film.has_halves());
  CHECK(all.film.per_pixel_relative_error() == Approx(one.film.per_pixel_relative_error()).epsilon(1e-12));
  CHECK(all.film.per_pixel_relative_error() < all.film.sample_variance_relative_error());
  // With --keep-halves the .exr keeps them (film.Yhalf, pt:halves): a part read back, alone or
  // as a merge of one, knows the halves its render knew, and so does a merge written and read
  // again. Without it the .exr has no such channels: the same channels however it was split.
  const std::string plain = render_part(stage3::kernels(), scene, s, 0, 64, "h_plain.exr");
  CHECK_FALSE(read_film_part(plain).film.has_halves());
  CHECK_FALSE(read_film_part(plain).kept_halves);
  const std::string whole = render_part(stage3::kernels(), scene, s, 0, 64, "h_whole.exr", true);
  const FilmPart read = read_film_part(whole);
  CHECK(read.kept_halves);
  CHECK(read.film.has_halves());
  CHECK(read.film.first_half_spp() == 32);
  CHECK(same_bits(read.film.first_half_luminance(), one.film.first_half_luminance()));
  CHECK(read.film.per_pixel_relative_error() == Approx(one.film.per_pixel_relative_error()).epsilon(1e-12));
  CHECK(merge_film_parts({read_film_part(whole)}, notes).film.has_halves());
  const std::string ka = render_part(stage3::kernels(), scene, s, 0, 16, "hk_a.exr", true);
  const std::string kc = render_part(stage3::kernels(), scene, s, 32, 32, "hk_c.exr", true);
  CHECK(read_film_part(ka).film.first_half_spp() == 8);  // samples 0 .. 15: halves 0:8 and 8:8
  CHECK(read_film_part(kc).film.first_half_spp() == 16);  // samples 32 .. 63: 32:16 and 48:16
  const std::string kb = render_part(stage3::kernels(), scene, s, 16, 16, "hk_b.exr", true);
  const FilmPart kept = merge_film_parts({read_film_part(kc), read_film_part(ka), read_film_part(kb)}, notes);
  CHECK(kept.kept_halves);  // pt_merge writes them again
  CHECK(kept.film.has_halves());
  CHECK_FALSE(merge_film_parts({read_film_part(a), read_film_part(b)}, notes).kept_halves);
  ImageMetadata meta;
  meta.stage = all.id.stage, meta.backend = all.backend, meta.film = &all.film, meta.identity = all.id;
  meta.ranges = all.ranges, meta.keep_halves = true, meta.seed = all.id.seed;
  const std::string all_path = scratch("h_all.exr").string();
  OutputFile(all_path).write(all.film.mean_rgb(), 8, 8, meta);
  CHECK(read_film_part(all_path).film.per_pixel_relative_error() ==
        Approx(one.film.per_pixel_relative_error()).epsilon(1e-12));
  // Samples 16 .. 63 are no aligned block; with a gap the halves are not known either.
  CHECK(!merge_film_parts({read_film_part(b), read_film_part(c)}, notes).film.has_halves());
  const FilmPart gap = merge_film_parts({read_film_part(a), read_film_part(c)}, notes);
  CHECK(!gap.film.has_halves());
  CHECK(gap.film.per_pixel_relative_error() == gap.film.sample_variance_relative_error());
  // Independent samples: the sample variance's figure, merged or not.
  s.sampler = kSamplerIndependent;
  const std::string ia = render_part(stage3::kernels(), scene, s, 0, 32, "h_ia.exr");
  const std::string ib = render_part(stage3::kernels(), scene, s, 32, 32, "h_ib.exr");
  CHECK(!merge_film_parts({read_film_part(ia), read_film_part(ib)}, notes).film.has_halves());
}
