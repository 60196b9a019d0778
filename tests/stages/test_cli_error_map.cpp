// The per-pixel error as users see it: the stage program's summary prints its estimate, and
// --error-map draws it (an .exr of the values whose RMS is the printed figure, a grey .png),
// refused in one line where it cannot be written. Not in the article: the programs' machinery.
#include <catch2/catch.hpp>

#include "tests/support/cli_run.h"

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>

namespace fs = std::filesystem;

namespace test_cli_error_map {  // this file's names: the unity build compiles it with others (tests/CMakeLists.txt)

namespace {

using pt_test::Run;

fs::path scratch() { return pt_test::scratch_dir("pt_cli"); }

Run run(const std::string& args, const std::string& env = "") {
  return pt_test::run_program(PT_STAGE1_BIN, args, env, scratch());
}

void check_error(const Run& r, int code, const std::string& words) {
  pt_test::check_error(r, "stage1_raycast", code, words);
}

}  // namespace

TEST_CASE("cli: the summary prints the per-pixel error, and --error-map draws it", "[cli]") {
  // Stage1 on the box: jittered positions make the edge pixels noisy, the others exact.
  std::string exr = (scratch() / "map.exr").string(), png = (scratch() / "map.png").string();
  // Independent samples: the printed figure is the RMS of the map's, each pixel's sample
  // variance over spp.
  Run r = run("--backend cpu --width 16 --height 16 --spp 16 --sampler independent --out " +
              (scratch() / "m.exr").string() + " --error-map " + exr);
  INFO(r.err);
  REQUIRE(r.code == 0);
  const std::string key = "estimated per-pixel relative error ";
  std::size_t at = r.out.find(key);
  REQUIRE(at != std::string::npos);
  double printed = std::stod(r.out.substr(at + key.size()));
  CHECK(r.out.find(", image-mean error ") != std::string::npos);
  // The map's values: each pixel's standard error over the image's mean, whose RMS is the
  // printed figure (printed to 2 digits).
  auto in = OIIO::ImageInput::open(exr);
  REQUIRE(in);
  std::vector<float> map(16 * 16 * 3);
  REQUIRE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, map.data()));
  double sum2 = 0.0;
  for (std::size_t i = 0; i < map.size(); i += 3) sum2 += double(map[i]) * map[i];
  CHECK(printed > 0.0);
  CHECK(std::sqrt(sum2 / 256.0) == Approx(printed).epsilon(0.05));
  // The default sampler at 16 spp: the map draws whichever estimate the summary printed,
  // so its RMS is the printed figure again (tests/common/app/test_error_map.cpp).
  Run q = run("--backend cpu --width 16 --height 16 --spp 16 --out " + (scratch() / "q.exr").string() +
              " --error-map " + exr);
  REQUIRE(q.code == 0);
  at = q.out.find(key);
  REQUIRE(at != std::string::npos);
  double printed_sobol = std::stod(q.out.substr(at + key.size()));
  auto sobol_map = OIIO::ImageInput::open(exr);
  REQUIRE(sobol_map);
  REQUIRE(sobol_map->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, map.data()));
  sum2 = 0.0;
  for (std::size_t i = 0; i < map.size(); i += 3) sum2 += double(map[i]) * map[i];
  CHECK(printed_sobol > 0.0);
  CHECK(std::sqrt(sum2 / 256.0) == Approx(printed_sobol).epsilon(0.05));
  // The PNG: grey, white at 2 x the target.
  Run p = run("--backend cpu --width 16 --height 16 --target-error 0.5 --out " + (scratch() / "m.png").string() +
              " --error-map " + png);
  REQUIRE(p.code == 0);
  auto grey = OIIO::ImageInput::open(png);
  REQUIRE(grey);
  CHECK(grey->spec().width == 16);
  // A map that cannot be written: exit 5 (2 for an unknown type) before rendering, naming --error-map.
  check_error(run("--backend cpu --out " + (scratch() / "x.png").string() + " --error-map /proc/no_such_place/m.png"), 5,
              "/proc/no_such_place/m.png");
  check_error(run("--backend cpu --out " + (scratch() / "x.png").string() + " --error-map m.txt"), 2, "--error-map");
  Run help = run("--help");
  CHECK(help.out.find("--error-map") != std::string::npos);
  CHECK(help.out.find("per-pixel relative error") != std::string::npos);
}

}  // namespace test_cli_error_map
