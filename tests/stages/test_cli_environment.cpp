// The environment map's options as users run them (issue #49; beyond the article, whose sky
// is one colour): --env, --env-strength, --env-rotate on stage1_raycast and
// stage4_direct_indirect. Bad input gets one line on stderr and the contract's exit code
// (2 option, 3 scene), and an existing --out file is left as it was.
#include <catch2/catch.hpp>

#include "tests/support/cli_run.h"

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>

namespace fs = std::filesystem;

namespace test_cli_environment {  // this file's names: the unity build compiles it with others (tests/CMakeLists.txt)

namespace {

using pt_test::Run;

fs::path scratch() { return pt_test::scratch_dir("pt_cli_env"); }

// The stage programs: stage1's path is built in (PT_STAGE1_BIN), stage4 lies beside it.
std::string program(const std::string& name) {
  if (name == "stage1_raycast") return PT_STAGE1_BIN;
  return (fs::path(PT_STAGE1_BIN).parent_path() / name).string();
}

const std::vector<std::string> kPrograms = {"stage1_raycast", "stage4_direct_indirect"};

Run run(const std::string& name, const std::string& args) {
  return pt_test::run_program(program(name), "--backend cpu --width 16 --height 12 --spp 2 " + args, "", scratch());
}

// A small equirectangular map (8 x 4, a bright top row; or black) written with OpenImageIO.
std::string good_map(bool black = false) {
  fs::path path = scratch() / (black ? "black.hdr" : "sky.hdr");
  if (fs::exists(path)) return path.string();
  std::vector<float> rgb(3 * 8 * 4, black ? 0.0f : 0.4f);
  for (int i = 0; i < 3 * 8; i++) rgb[i] = black ? 0.0f : 3.0f;
  auto out = OIIO::ImageOutput::create(path.string());
  REQUIRE(out);
  REQUIRE(out->open(path.string(), OIIO::ImageSpec(8, 4, 3, OIIO::TypeDesc::FLOAT)));
  REQUIRE(out->write_image(OIIO::TypeDesc::FLOAT, rgb.data()));
  out->close();
  return path.string();
}

// Runs a bad command line with --out naming an existing file: the error's shape, and the
// file left untouched.
void check_refused(const std::string& name, const std::string& args, int code, const std::string& words) {
  fs::path keep = scratch() / "keep.exr";
  std::ofstream(keep, std::ios::binary) << "a file the user made";
  Run r = run(name, args + " --out " + keep.string());
  INFO(name << " " << args);
  pt_test::check_error(r, name, code, words);
  CHECK(pt_test::read_file(keep) == "a file the user made");
}

}  // namespace

TEST_CASE("cli environment: the programs are built", "[environment][cli]") {
  for (const std::string& name : kPrograms) {
    INFO(program(name) << ": build the target " << name);
    CHECK(fs::exists(program(name)));
  }
}

TEST_CASE("cli environment: a bad option combination or value exits 2 with one line", "[environment][cli]") {
  if (!fs::exists(program("stage4_direct_indirect"))) return;  // the test above says so
  std::string map = good_map();
  for (const std::string& name : kPrograms) {
    check_refused(name, "--env " + map + " --sky 1,1,1", 2, "--sky");
    check_refused(name, "--env-strength 2", 2, "--env-strength");
    check_refused(name, "--env-rotate 10", 2, "--env-rotate");
    check_refused(name, "--env " + map + " --env-strength -1", 2, "--env-strength");
    check_refused(name, "--env " + map + " --env-strength nan", 2, "--env-strength");
    check_refused(name, "--env " + map + " --env-rotate inf", 2, "--env-rotate");
    check_refused(name, "--env " + (scratch() / "sky.png").string(), 2, "sky.png");
  }
}

TEST_CASE("cli environment: a missing or broken map exits 3 with one line", "[environment][cli]") {
  if (!fs::exists(program("stage4_direct_indirect"))) return;
  std::ofstream(scratch() / "broken.exr") << "not an image";
  for (const std::string& name : kPrograms) {
    check_refused(name, "--env " + (scratch() / "missing.hdr").string(), 3, "missing.hdr");
    check_refused(name, "--env " + (scratch() / "broken.exr").string(), 3, "broken.exr");
  }
}

TEST_CASE("cli environment: a good map (or a black one) renders, the summary says so, stage4 states the sky's pick "
          "probability", "[environment][cli]") {
  if (!fs::exists(program("stage4_direct_indirect"))) return;
  for (int i = 0; i < 4; i++) {
    const std::string& name = kPrograms[i / 2];
    const bool black = i % 2;
    fs::path out = scratch() / (name + (black ? "_black.exr" : ".exr"));
    Run r = run(name, "--env " + good_map(black) + " --env-strength 0.5 --env-rotate 30 --out " + out.string());
    INFO(name << " stderr: " << r.err << "\nstdout: " << r.out);
    REQUIRE(r.code == 0);
    CHECK(fs::exists(out));
    CHECK(pt_test::lines(r.out) == 1);
    CHECK(r.out.find("environment map") != std::string::npos);
    if (name == "stage4_direct_indirect") CHECK(r.err.find("light sampling picks it with probability") != std::string::npos);
  }
}

}  // namespace test_cli_environment
