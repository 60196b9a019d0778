// stage5_mis's --mis option (docs/stage5_mis.md, "Weights from a pilot"): pilot, the default,
// says on the summary line what its pilot chose; power leaves the pilot out. A bad value is
// one line and exit 2, and pt_merge refuses to merge parts rendered with the two weights.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "tests/support/cli_run.h"

namespace fs = std::filesystem;
using namespace pt_test;

namespace {

fs::path scratch() { return scratch_dir("pt_stage5_cli"); }
std::string path(const std::string& name) { return (scratch() / name).string(); }

Run stage5(const std::string& args) {
  return run_program(PT_STAGE5_BIN, "--backend cpu --scene builtin:floor_large_light --width 16 --height 12 " + args, "",
                     scratch());
}

}  // namespace

TEST_CASE("cli: stage5's --mis pilot says what its pilot chose, --mis power runs without it", "[stage5][cli]") {
  Run pilot = stage5("--spp 4 --out " + path("pilot.exr"));
  INFO(pilot.err);
  REQUIRE(pilot.code == 0);
  CHECK(pilot.out.find("[mis pilot: 16x12, light pdf x") != std::string::npos);
  Run power = stage5("--spp 4 --mis power --out " + path("power.exr"));
  REQUIRE(power.code == 0);
  CHECK(power.out.find("[mis pilot") == std::string::npos);
  check_error(stage5("--mis balance --out " + path("x.exr")), "stage5_mis", 2, "--mis");
  Run help = run_program(PT_STAGE5_BIN, "--help", "", scratch());
  CHECK(help.out.find("--mis") != std::string::npos);
  // Parts rendered with the two weights are two estimators: not one render's parts.
  REQUIRE(stage5("--samples 4:4 --mis power --out " + path("second.exr")).code == 0);
  check_error(run_program(PT_MERGE_BIN, "--out " + path("m.exr") + " " + path("pilot.exr") + " " + path("second.exr"), "",
                          scratch()),
              "pt_merge", 3, "second.exr' is a part of another render");
  REQUIRE(stage5("--samples 4:4 --out " + path("second_pilot.exr")).code == 0);
  Run merged = run_program(PT_MERGE_BIN, "--out " + path("m.exr") + " " + path("pilot.exr") + " " + path("second_pilot.exr"),
                           "", scratch());
  INFO(merged.err);
  CHECK(merged.code == 0);
}
