// What a merge of film parts refuses (common/app/film_file.h, pt_merge): parts of another
// render, samples held twice, an .exr without the film's channels, header numbers that are
// not strictly numbers, ranges that overflow; and the pass schedule the parts split at.
// Not part of the article: the machinery of the stage programs' --samples and pt_merge.
#include <catch2/catch.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "common/app/exr_file.h"
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
