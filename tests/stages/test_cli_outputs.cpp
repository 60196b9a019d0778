// The stage programs' outputs as users name them (docs/reliability.md, issue "Nothing lost"):
// options that would lose a file or pass as "off" are refused with one line; --out through
// a link, a long name, a killed run's temporary file, --resume PATH's checkpoint and a PNG's
// metadata behave as a user expects. The full-disk cases are tests/stages/full_disk_test.sh.
// Not part of the article: the machinery of the stage programs.
#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <OpenImageIO/imageio.h>

#include "common/app/replace_file.h"
#include "tests/support/cli_run.h"

namespace fs = std::filesystem;

namespace test_cli_outputs {  // this file's names: the unity build compiles it with others (tests/CMakeLists.txt)

namespace {

using pt_test::Run;

fs::path scratch() { return pt_test::scratch_dir("pt_cli_outputs"); }

std::string path(const std::string& name) { return (scratch() / name).string(); }

Run run(const std::string& args) { return pt_test::run_program(PT_STAGE1_BIN, args, "", scratch()); }

void check_error(const Run& r, int code, const std::string& words) {
  pt_test::check_error(r, "stage1_raycast", code, words);
}

const std::string kSmall = "--backend cpu --threads 2 --width 24 --height 16 ";

}  // namespace

TEST_CASE("cli: NaN for --checkpoint, --time-budget or --target-error is refused, not taken as off",
          "[reliability][output]") {
  for (const char* option : {"--checkpoint", "--time-budget", "--target-error"}) {
    INFO(option);
    check_error(run(kSmall + option + " nan --out " + path("nan.png")), 2, "NaN");
    CHECK_FALSE(fs::exists(path("nan.png")));
  }
}

TEST_CASE("cli: --out and --error-map naming one file are refused before rendering, the file kept",
          "[reliability][output]") {
  const std::string image = path("same.exr");
  std::ofstream(image) << "the user's file";
  check_error(run(kSmall + "--spp 4 --out " + image + " --error-map " + image), 2, "is the same file as --out");
  fs::remove(path("same_link.exr"));
  fs::create_symlink("same.exr", path("same_link.exr"));
  check_error(run(kSmall + "--spp 4 --out " + image + " --error-map " + path("same_link.exr")), 2, "same file");
  check_error(run(kSmall + "--spp 4 --out " + image + " --resume " + image), 2, "same file");
  CHECK(pt_test::read_file(image) == "the user's file");
}

TEST_CASE("cli: --out through a symbolic link writes its target; a FIFO or a device is refused at once",
          "[reliability][output]") {
  fs::create_directories(scratch() / "renders");
  const std::string target = path("renders/final.png"), link = path("final_link.png");
  fs::remove(target), fs::remove(link);
  fs::create_symlink("renders/final.png", link);
  Run r = run(kSmall + "--out " + link);
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(fs::is_symlink(link));
  CHECK(fs::is_regular_file(target));
  const std::string fifo = path("pipe.png");
  fs::remove(fifo);
  REQUIRE(::mkfifo(fifo.c_str(), 0644) == 0);
  check_error(run(kSmall + "--out " + fifo), 5, "it is a FIFO (named pipe), not a file");  // never opened: no hang
  CHECK(fs::is_fifo(fifo));
  fs::remove(path("null.png"));
  fs::create_symlink("/dev/null", path("null.png"));
  check_error(run(kSmall + "--out " + path("null.png")), 5, "it is a device, not a file");
  CHECK(fs::is_character_file("/dev/null"));
}

TEST_CASE("cli: an output name of 241 to 255 bytes is written; a longer one is refused as too long",
          "[reliability][output]") {
  for (int length : {241, 250, 255}) {
    const std::string name = path(std::string(std::size_t(length) - 4, 'x') + ".exr");
    Run r = run(kSmall + "--out " + name);
    INFO(length << " " << r.err);
    CHECK(r.code == 0);
    CHECK(fs::is_regular_file(name));
    fs::remove(name);
  }
  check_error(run(kSmall + "--out " + path(std::string(296, 'x') + ".exr")), 2, "longer than the 255");
}

TEST_CASE("cli: a temporary file left by a killed render of the same output is removed by the next",
          "[reliability][output]") {
  const std::string out = path("after_kill.exr");
  const long dead = pt_test::dead_pid();
  const std::string left = pt::temporary_path(out, dead);
  const std::string old_style = path(".after_kill.exr.tmp" + std::to_string(dead) + ".exr");
  std::ofstream(left) << "half an image";
  std::ofstream(old_style) << "half an image";
  Run r = run(kSmall + "--out " + out);
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK_FALSE(fs::exists(left));
  CHECK_FALSE(fs::exists(old_style));
}

TEST_CASE("cli: a PNG's pt:seed metadata is the render's seed", "[reliability][output]") {
  const std::string out = path("seed.png");
  REQUIRE(run(kSmall + "--seed 7 --out " + out).code == 0);
  auto in = OIIO::ImageInput::open(out);
  REQUIRE(in);
  CHECK(std::string(in->spec().get_string_attribute("pt:seed")) == "7");
}

TEST_CASE("cli: --resume PATH continues PATH, saves to it, and removes it when done; <out>.ckpt is left alone",
          "[reliability][checkpoint]") {
  const std::string out = path("resumed.exr"), elsewhere = path("saved_elsewhere.ckpt");
  fs::remove(out + ".ckpt"), fs::remove(elsewhere);
  Run first = run(kSmall + "--spp 4000000 --time-budget 0.3 --checkpoint 0.01 --out " + out);
  REQUIRE(first.code == 0);
  REQUIRE(fs::exists(out + ".ckpt"));
  fs::rename(out + ".ckpt", elsewhere);
  std::ofstream(out + ".ckpt") << "not this run's";
  // Stopped early again: PATH holds the new state (more samples than before).
  const auto before = fs::last_write_time(elsewhere);
  Run again = run(kSmall + "--spp 4000000 --time-budget 0.3 --checkpoint 0.01 --resume " + elsewhere + " --out " + out);
  INFO(again.err);
  REQUIRE(again.code == 0);
  CHECK(fs::last_write_time(elsewhere) != before);
  // Finished: PATH is removed, <out>.ckpt (not this run's) stays. The refusal of too small
  // an --spp says how many samples PATH holds.
  Run ask = run(kSmall + "--spp 1 --resume " + elsewhere + " --out " + out);
  const std::size_t at = ask.err.find(" has ");
  REQUIRE(at != std::string::npos);
  const unsigned long long held = std::stoull(ask.err.substr(at + 5));
  Run done = run(kSmall + "--spp " + std::to_string(held + 16) + " --resume " + elsewhere + " --out " + out);
  INFO(done.err);
  CHECK(done.code == 0);
  CHECK_FALSE(fs::exists(elsewhere));
  CHECK(pt_test::read_file(out + ".ckpt") == "not this run's");
}

TEST_CASE("cli: a folder given to --resume is named as a folder", "[reliability][checkpoint]") {
  check_error(run(kSmall + "--spp 4 --resume " + scratch().string() + " --out " + path("r.exr")), 2, "is a folder");
}

}  // namespace test_cli_outputs
