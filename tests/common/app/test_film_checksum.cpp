// A part's checksum and the sample-count checks (common/app/film_file.h, pt:checksum): the
// checksum covers what identifies the render, the samples it holds and every pixel's bits,
// so an edited or damaged part is refused; a header whose count disagrees with the film's
// own numbers is refused even when its checksum was computed again. Not part of the
// article: machinery of pt_merge and pt_compare (issue 45, "pt_merge trusts what it reads").
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "common/app/exr_file.h"
#include "common/app/film_file.h"
#include "common/app/image_output.h"
#include "common/base/error.h"

namespace fs = std::filesystem;
using namespace pt;

namespace test_film_checksum {  // this file's names: the unity build compiles it with others (tests/CMakeLists.txt)

namespace {

fs::path scratch(const std::string& name) {
  fs::path dir = fs::temp_directory_path() / ("pt_film_checksum_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

// A film of `spp` grey samples a pixel, as a stage writes it: a third of the pixels alike in
// every sample (a light, a flat wall), the others varying; the halves kept.
ExrImage synthetic_part(const std::string& name, int spp) {
  const int width = 8, height = 6;
  Film film(width, height);
  film.track_halves(0);
  std::vector<glm::vec4> pass(std::size_t(width) * std::size_t(height));
  for (int s = 0; s < spp; s++) {
    for (std::size_t i = 0; i < pass.size(); i++) {
      const float v = i % 3 == 0 ? 0.5f : 0.25f + 0.5f * float((i * 7 + std::size_t(s) * 13) % 5) / 4.0f;
      pass[i] = glm::vec4(v, v, v, v);
    }
    film.add_pass(pass, 1);
  }
  ImageMetadata meta;
  meta.stage = "synthetic", meta.backend = "none", meta.scene = "none", meta.spp = std::uint64_t(spp), meta.seed = 5;
  meta.film = &film;
  meta.identity = {"synthetic", "0123456789abcdef", "8x6", 5};
  meta.ranges = {{0, std::uint64_t(spp)}};
  meta.keep_halves = true;
  const std::string path = scratch(name).string();
  OutputFile(path).write(film.mean_rgb(), width, height, meta);
  ExrImage image;
  std::string why;
  REQUIRE(read_exr(path, image, why));
  return image;
}

// Computes the checksum again, as whoever edits a part on purpose can.
void reseal(ExrImage& image) {
  image.set_attribute(kFilmChecksumAttribute,
                film_checksum(image, image.attribute("pt:stage"), image.attribute("pt:seed")));
}

// film_part_of's refusal of `image`, or "" where it reads it.
std::string refusal(const ExrImage& image) {
  try {
    film_part_of(image, "edited.exr");
  } catch (const Error& e) {
    CHECK(e.code() == kExitBadScene);
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("film parts: pt:checksum covers the render's identity, its samples and every pixel's bits; other "
          "attributes may change",
          "[film][parts][reliability]") {
  const ExrImage image = synthetic_part("sum.exr", 16);
  REQUIRE(image.attribute(kFilmChecksumAttribute).size() == 16);
  REQUIRE(image.attribute("pt:halves") == "0:8");
  CHECK(refusal(image).empty());
  CHECK(film_part_of(image, "sum.exr").checksummed);
  // What the merge compares and counts: any edit is refused, naming the file and the checksum.
  const std::pair<const char*, const char*> edits[] = {
      {"pt:stage", "stage1_raycast"}, {"pt:scene_hash", "0123456789abcdee"}, {"pt:options", "8x6, edited"},
      {"pt:seed", "6"},           {"pt:samples", "16:16"},            {"pt:halves", "0:4"}};
  for (const auto& [name, value] : edits) {
    INFO(name << " -> " << value);
    ExrImage edited = image;
    edited.set_attribute(name, value);
    CHECK_THAT(refusal(edited), Catch::Contains("'edited.exr'") && Catch::Contains("pt:checksum"));
  }
  // One bit of any channel of any pixel.
  const std::size_t channels = image.channels.size();
  for (std::size_t c = 0; c < channels; c++) {
    for (std::uint32_t bit : {0u, 31u}) {
      INFO("channel " << image.channels[c] << ", bit " << bit);
      ExrImage edited = image;
      edited.pixels[(c * 5 % 48) * channels + c] ^= 1u << bit;
      CHECK_THAT(refusal(edited), Catch::Contains("pt:checksum"));
    }
  }
  // What is there for the reader only.
  for (const char* name : {"pt:scene", "pt:backend", "pt:spp", "pt:seconds", "Software", "comments"}) {
    INFO(name);
    ExrImage edited = image;
    edited.set_attribute(name, "edited");
    CHECK(refusal(edited).empty());
  }
  // The channels' order in memory does not matter (an .exr stores them by name).
  ExrImage reordered = image;
  for (std::size_t p = 0; p < image.pixels.size() / channels; p++) {
    std::swap(reordered.pixels[p * channels], reordered.pixels[p * channels + channels - 1]);
  }
  std::swap(reordered.channels.front(), reordered.channels.back());
  const bool first_is_uint = reordered.is_uint.front();
  reordered.is_uint.front() = reordered.is_uint.back();
  reordered.is_uint.back() = first_is_uint;
  CHECK(refusal(reordered).empty());
}

TEST_CASE("film parts: a part without pt:checksum, written before parts carried one, is read and merged with a note",
          "[film][parts][reliability]") {
  ExrImage old = synthetic_part("old.exr", 16);
  old.set_attribute(kFilmChecksumAttribute, "");
  const FilmPart part = film_part_of(old, "old.exr");
  CHECK_FALSE(part.checksummed);
  CHECK_THAT(unchecked_note(part), Catch::Contains("'old.exr' has no pt:checksum") && Catch::Contains("render it again"));
  CHECK(unchecked_note(film_part_of(synthetic_part("new.exr", 16), "new.exr")).empty());
  std::vector<std::string> notes;
  merge_film_parts({part}, notes);
  REQUIRE(notes.size() == 1);
  CHECK(notes[0] == unchecked_note(part));
  // Its header is still held to its film's numbers (below).
  old.set_attribute("pt:samples", "0:8");
  CHECK_THAT(refusal(old), Catch::Contains("claims 8 samples in its pt:samples"));
}

TEST_CASE("film parts: a header that claims another sample count than its film holds is refused even with its "
          "checksum computed again",
          "[film][parts][reliability]") {
  const ExrImage image = synthetic_part("count.exr", 32);
  // Fewer: the pixels whose samples are alike need all 32 (Cauchy-Schwarz); the merge would
  // be too bright.
  for (const char* fewer : {"0:16", "0:31", "0:1"}) {
    INFO("pt:samples " << fewer);
    ExrImage edited = image;
    edited.set_attribute("pt:samples", fewer);
    edited.set_attribute("pt:halves", "");
    reseal(edited);
    CHECK_THAT(refusal(edited), Catch::Contains("'edited.exr'") && Catch::Contains("samples in its pt:samples") &&
                                    Catch::Contains("holds at least 3"));
  }
  // More: the variance the writer computed (Y.variance) belongs to 32; the merge would be too dark.
  for (const char* more : {"0:33", "0:64", "32:64", "0:4294967296"}) {
    INFO("pt:samples " << more);
    ExrImage edited = image;
    edited.set_attribute("pt:samples", more);
    edited.set_attribute("pt:halves", "");
    reseal(edited);
    CHECK_THAT(refusal(edited), Catch::Contains("samples in its pt:samples") && Catch::Contains("Y.variance"));
  }
  // The count it holds, in another range, passes: the numbers cannot tell which samples they are.
  ExrImage moved = image;
  moved.set_attribute("pt:samples", "64:32");
  moved.set_attribute("pt:halves", "");
  reseal(moved);
  CHECK(refusal(moved).empty());
}

}  // namespace test_film_checksum
