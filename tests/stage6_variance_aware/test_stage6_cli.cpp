// The stage6_variance_aware program as a user runs it (the contract, /README.md; beyond the
// article): its summary line carries what its pilot chose, its --help lists the roulette's
// options with stage6's default, and a bad option gets one line and exit code 2.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <utility>

#include "tests/support/cli_run.h"

namespace fs = std::filesystem;

namespace test_stage6_cli {  // this file's names: the unity build compiles it with others (tests/CMakeLists.txt)

namespace {

using pt_test::Run;

fs::path scratch() { return pt_test::scratch_dir("pt_cli_stage6"); }

Run run_stage6(const std::string& args) { return pt_test::run_program(PT_STAGE6_BIN, args, "", scratch()); }

}  // namespace

TEST_CASE("stage6 cli: the summary line ends with the pilot's note, the light pdf's factors it chose", "[stage6][cli]") {
  std::string out = (scratch() / "small_light.exr").string();
  Run r = run_stage6("--backend cpu --scene builtin:floor_small_light --width 48 --height 24 --spp 4 --out " + out);
  INFO("stdout: " << r.out << "stderr: " << r.err);
  REQUIRE(r.code == 0);
  CHECK(pt_test::lines(r.out) == 1);
  CHECK(r.out.rfind("stage6_variance_aware: backend cpu", 0) == 0);
  CHECK(r.out.find("48x24, 4 spp") != std::string::npos);
  // A 32-pixel pilot of the view's shape; the small light: the light sample counts more.
  const std::size_t note = r.out.find(" [mis pilot: 32x16, light pdf x");
  REQUIRE(note != std::string::npos);
  CHECK(r.out.find(" at diffuse, x1 at glossy vertices]\n", note) != std::string::npos);
  CHECK(r.out.find("light pdf x1 at diffuse") == std::string::npos);
  CHECK(fs::file_size(out) > 0);
}

TEST_CASE("stage6 cli: --help lists --rr (default throughput) and --depth-cap", "[stage6][cli]") {
  Run r = run_stage6("--help");
  INFO(r.out);
  REQUIRE(r.code == 0);
  CHECK(r.err.empty());
  CHECK(r.out.find("--rr") != std::string::npos);
  CHECK(r.out.find("{fixed,throughput}=throughput") != std::string::npos);  // stage6's default
  CHECK(r.out.find("--depth-cap") != std::string::npos);
  CHECK(r.out.find("builtin:cornell") != std::string::npos);
}

TEST_CASE("stage6 cli: a bad option exits 2 with one line naming it and writes no image", "[stage6][cli]") {
  const fs::path out = scratch() / "never.png";
  fs::remove(out);
  // --mis: the pilot's factors are no option (issue #48: the pilot chooses them).
  const std::pair<std::string, std::string> bad[] = {
      {"--rr sometimes", "--rr"}, {"--depth-cap 0", "--depth-cap"}, {"--mis 4", "--mis"}, {"--spp 0", "--spp"}};
  for (const auto& [args, words] : bad) {
    Run r = run_stage6("--backend cpu --width 8 --height 8 " + args + " --out " + out.string());
    INFO(args);
    pt_test::check_error(r, "stage6_variance_aware", 2, words);
    CHECK(r.err.find("--help") != std::string::npos);  // what to do
    CHECK(r.out.empty());
    CHECK_FALSE(fs::exists(out));
  }
}

}  // namespace test_stage6_cli
