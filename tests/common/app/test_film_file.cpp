// Parts of one render and their merge (common/app/film_file.h, the stages' --samples
// FIRST:COUNT and pt_merge): any split of the samples 0 ... N-1 into ranges, rendered
// apart, written as .exr parts, read back and merged, is the one-run image: bit for bit
// when the ranges split at the pass schedule's ends (its variance sums to double rounding),
// to float rounding otherwise. A merge
// can be merged again; parts of another render and samples held twice are refused.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "common/app/exr_file.h"
#include "common/app/film_file.h"
#include "common/app/image_output.h"
#include "common/base/error.h"
#include "common/scene/scene_loading.h"
#include "stage3_importance/kernels.h"
#include "stage4_direct_indirect/kernels.h"
#include "tests/support/test_render.h"

namespace fs = std::filesystem;
using namespace pt;
using namespace pt::test;

namespace {

fs::path scratch(const std::string& name) {
  fs::path dir = fs::temp_directory_path() / ("pt_film_file_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

// Renders the samples [first, first + count) of `scene` on the CPU and writes them as a part.
std::string render_part(const StageKernels& kernels, const Scene& scene, RenderSettings s, std::uint64_t first,
                        std::uint64_t count, const std::string& name, bool keep_halves = false) {
  s.first_sample = first, s.spp = count;
  std::unique_ptr<Backend> backend = make_backend("cpu", kernels);
  RenderResult r = render(*backend, scene, s);
  REQUIRE(r.film.spp() == count);
  ImageMetadata meta;
  meta.stage = kernels.name, meta.backend = "cpu", meta.scene = scene.name, meta.spp = count, meta.seed = s.seed;
  meta.film = &r.film;
  meta.identity = film_identity(kernels.name, scene, s);
  meta.ranges = {{first, count}};
  meta.keep_halves = keep_halves;
  const std::string path = scratch(name).string();
  OutputFile(path).write(r.film.mean_rgb(), s.width, s.height, meta);
  return path;
}

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

std::string merge_error(std::vector<FilmPart> parts) {
  std::vector<std::string> notes;
  try {
    merge_film_parts(std::move(parts), notes);
  } catch (const Error& e) {
    CHECK(e.code() == kExitBadScene);
    return e.what();
  }
  return "";
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

TEST_CASE("film parts: parts of another render or samples held twice are refused, naming the file and the field; "
          "a gap is said",
          "[stage3][stage4][film][parts]") {
  const Scene scene = make_builtin_scene("furnace");
  RenderSettings s = settings(8, 8, 16, 13);
  s.roulette = kRouletteThroughput;
  const FilmPart base = read_film_part(render_part(stage4::kernels(), scene, s, 0, 16, "r_base.exr"));
  RenderSettings other_seed = s;
  other_seed.seed = 14;
  RenderSettings other_sky = s;
  other_sky.sky = glm::vec3(1.0f);
  RenderSettings other_size = s;
  other_size.width = 9;
  Scene other_scene = scene;
  other_scene.materials[0].base_color *= 0.5f;
  CHECK_THAT(merge_error({base, read_film_part(render_part(stage4::kernels(), scene, other_seed, 16, 16, "r_seed.exr"))}),
             Catch::Contains("r_seed.exr") && Catch::Contains("seed"));
  CHECK_THAT(merge_error({base, read_film_part(render_part(stage4::kernels(), scene, other_sky, 16, 16, "r_sky.exr"))}),
             Catch::Contains("options") && Catch::Contains("sky"));
  CHECK_THAT(merge_error({base, read_film_part(render_part(stage4::kernels(), scene, other_size, 16, 16, "r_size.exr"))}),
             Catch::Contains("options"));
  CHECK_THAT(merge_error({base, read_film_part(render_part(stage4::kernels(), other_scene, s, 16, 16, "r_scene.exr"))}),
             Catch::Contains("scene"));
  CHECK_THAT(merge_error({base, read_film_part(render_part(stage3::kernels(), scene, s, 16, 16, "r_stage.exr"))}),
             Catch::Contains("stage"));
  CHECK_THAT(merge_error({base, read_film_part(render_part(stage4::kernels(), scene, s, 8, 16, "r_overlap.exr"))}),
             Catch::Contains("r_overlap.exr") && Catch::Contains("overlap") && Catch::Contains("8:16"));
  std::vector<std::string> notes;
  const FilmPart gap = merge_film_parts({base, read_film_part(render_part(stage4::kernels(), scene, s, 32, 16, "r_gap.exr"))}, notes);
  REQUIRE(notes.size() == 1);
  CHECK_THAT(notes[0], Catch::Contains("16:16"));
  CHECK(format_ranges(gap.ranges) == "0:16,32:16");
  CHECK(gap.film.spp() == 32);
}

TEST_CASE("film parts: an .exr without the film's channels, or not an image, is refused in one line",
          "[stage1][film][parts]") {
  const std::string rgb_only = scratch("rgb_only.exr").string();
  ImageMetadata meta;
  meta.stage = "stage1_raycast";
  OutputFile(rgb_only).write(std::vector<float>(4 * 4 * 3, 0.5f), 4, 4, meta);
  for (const std::string& path : {rgb_only, scratch("no_such.exr").string()}) {
    try {
      read_film_part(path);
      FAIL("read " << path);
    } catch (const Error& e) {
      CHECK(e.code() == kExitBadScene);
      CHECK_THAT(std::string(e.what()), Catch::Contains(path));
    }
  }
}

TEST_CASE("pass schedule: passes end at 1, 2, 4, 8, 16 and every multiple of 16", "[film][parts]") {
  const std::vector<std::uint64_t> ends = {1, 2, 4, 8, 16, 32, 48, 64};
  std::uint64_t at = 0;
  for (std::uint64_t end : ends) {
    CHECK(is_pass_end(at));
    for (std::uint64_t s = at; s < end; s++) CHECK(pass_end(s) == end);
    at = end;
  }
  for (std::uint64_t s : {3u, 5u, 15u, 17u, 33u, 47u}) CHECK_FALSE(is_pass_end(s));
  CHECK(pass_end(4294967280ull) == 4294967296ull);
}

// What a part's header says is read strictly (issue 45): a number is digits only, without
// sign, spaces, leading zeros or anything after it, and within its range; a sample range
// ends at sample index 2^32 at most and the ranges of one part ascend without overlap, so
// that no sum of counts overflows. Anything else names the file and the attribute, exit 3.
TEST_CASE("film parts: header numbers are read strictly: no sign, no junk, no overflow, within range",
          "[film][parts][reliability]") {
  for (const char* bad : {"1:18446744073709551615", "18446744073709551615:2", "18446744073709551616:1", "+0:4", "0:+4",
                          "-1:4", "0:-4", " 0:4", "0:4 ", "0:4,", ",0:4", "0:4,,8:4", "00:4", "0:04", "0x0:4", "0:4e0",
                          "0:0", "4294967295:2", "0:4294967297", "4294967296:1", "8:4,0:4", "0:8,4:8", "0:4:4", "0;4",
                          "", "0", ":"}) {
    INFO("pt:samples '" << bad << "'");
    try {
      parse_ranges(bad, "part.exr");
      FAIL("accepted");
    } catch (const Error& e) {
      CHECK(e.code() == kExitBadScene);
      CHECK_THAT(std::string(e.what()), Catch::Contains("'part.exr'") && Catch::Contains("pt:samples"));
    }
  }
  CHECK(format_ranges(parse_ranges("0:4", "p")) == "0:4");
  CHECK(format_ranges(parse_ranges("0:16,32:16,48:1", "p")) == "0:16,32:16,48:1");
  CHECK(format_ranges(parse_ranges("4294967295:1", "p")) == "4294967295:1");
  CHECK(format_ranges(parse_ranges("0:4294967296", "p")) == "0:4294967296");

  // The seed and the scene hash, in a part read back and edited in memory.
  const Scene scene = make_builtin_scene("furnace");
  RenderSettings s = settings(4, 4, 4, 21);
  const std::string file = render_part(stage3::kernels(), scene, s, 0, 4, "strict.exr");
  ExrImage image;
  std::string why;
  REQUIRE(read_exr(file, image, why));
  auto refused = [&](const char* name, const std::string& value) {
    ExrImage edited = image;
    for (auto& [key, text] : edited.text)
      if (key == name) text = value;
    try {
      film_part_of(edited, "edited.exr");
    } catch (const Error& e) {
      CHECK(e.code() == kExitBadScene);
      CHECK_THAT(std::string(e.what()), Catch::Contains("'edited.exr'") && Catch::Contains(name));
      return true;
    }
    return false;
  };
  for (const char* bad : {"21abc", "-21", "+21", "021", " 21", "21 ", "0x15", "4294967296", "99999999999999999999999"}) {
    INFO("pt:seed '" << bad << "'");
    CHECK(refused("pt:seed", bad));
  }
  for (const char* bad : {"0123", "0123456789abcdeg", "0123456789ABCDEF", "0123456789abcdef0", " 123456789abcdef"}) {
    INFO("pt:scene_hash '" << bad << "'");
    CHECK(refused("pt:scene_hash", bad));
  }
  CHECK_FALSE(refused("pt:seed", "21"));
}

TEST_CASE("film parts: ranges whose ends or sums would overflow are refused by the merge", "[film][parts][reliability]") {
  FilmPart a, b;
  a.path = "a.exr", b.path = "b.exr";
  a.id = b.id = {"stage1_raycast", "0123456789abcdef", "1x1", 1};
  a.film = Film(1, 1), b.film = Film(1, 1);
  a.film.restore(1, {1.0, 1.0, 1.0, 1.0});
  a.ranges = {{0, 1}};
  for (const SampleRange r : {SampleRange{1, ~std::uint64_t(0)}, SampleRange{~std::uint64_t(0), 2},
                              SampleRange{4294967295ull, 2}, SampleRange{5, 0}}) {
    INFO("range " << r.first << ":" << r.count);
    b.ranges = {r};
    b.film.restore(r.count, {1.0, 1.0, 1.0, 1.0});
    CHECK_THAT(merge_error({a, b}), Catch::Contains("b.exr"));
  }
}
