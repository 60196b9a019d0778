// One frame in parts from the command line (the contract (README.md), "Parts, merging and
// comparing"): --samples FIRST:COUNT on a stage, pt_merge on the .exr parts. Bad ranges are
// one line and exit 2; parts split at pass ends merge into the one-run image bit for bit; a
// part cut by Ctrl-C holds the samples it did and merges with the rest; pt_merge refuses a
// part of another render naming the file, and says where samples are missing.
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>

#include "common/app/film_file.h"
#include "tests/support/child_signals.h"
#include "tests/support/cli_run.h"

namespace fs = std::filesystem;
using namespace pt_test;

namespace {

fs::path scratch() { return scratch_dir("pt_cli_parts"); }
std::string path(const std::string& name) { return (scratch() / name).string(); }

Run stage1(const std::string& args) {
  return run_program(PT_STAGE1_BIN, "--backend cpu --width 12 --height 10 " + args, "", scratch());
}
Run merge(const std::string& args) { return run_program(PT_MERGE_BIN, args, "", scratch()); }

}  // namespace

TEST_CASE("cli: --samples FIRST:COUNT takes a range, and a bad one is one line and exit 2", "[stage1][cli][parts]") {
  for (const char* bad : {"8", "a:4", "4:", ":4", "4:0", "-1:4", "4294967295:2", "1:2:3"}) {
    INFO("--samples " << bad);
    check_error(stage1(std::string("--samples ") + bad + " --out " + path("bad.png")), "stage1_raycast", 2, "--samples");
  }
  check_error(stage1("--spp 4 --samples 0:4 --out " + path("both.png")), "stage1_raycast", 2, "--spp and --samples");
  Run r = stage1("--samples 4:4 --out " + path("range.exr"));
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find(", 4 spp,") != std::string::npos);
  pt::FilmPart part = pt::read_film_part(path("range.exr"));
  CHECK(pt::format_ranges(part.ranges) == "4:4");
  CHECK(part.film.spp() == 4);
}

TEST_CASE("cli: pt_merge of parts split at pass ends is the one-run image bit for bit", "[cli][parts]") {
  REQUIRE(stage1("--spp 48 --seed 9 --out " + path("one.exr")).code == 0);
  REQUIRE(stage1("--samples 0:16 --seed 9 --out " + path("a.exr")).code == 0);
  REQUIRE(stage1("--samples 16:32 --seed 9 --out " + path("b.exr")).code == 0);
  Run r = merge("--out " + path("m.exr") + " " + path("b.exr") + " " + path("a.exr"));
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.err.empty());
  CHECK(r.out.find("2 parts") != std::string::npos);
  CHECK(r.out.find("48 spp, samples 0:48") != std::string::npos);
  const pt::FilmPart one = pt::read_film_part(path("one.exr")), merged = pt::read_film_part(path("m.exr"));
  CHECK(merged.film.mean_rgb() == one.film.mean_rgb());
  // Refusals name the file and the field; a gap is said, and the merge still written.
  REQUIRE(stage1("--samples 48:16 --seed 10 --out " + path("seed10.exr")).code == 0);
  check_error(merge("--out " + path("x.exr") + " " + path("m.exr") + " " + path("seed10.exr")), "pt_merge", 3,
              "seed10.exr' is a part of another render: its seed");
  check_error(merge("--out " + path("x.exr") + " " + path("m.exr") + " " + path("a.exr")), "pt_merge", 3, "overlap");
  check_error(merge("--out " + path("x.png") + " " + path("a.exr")), "pt_merge", 2, "not an .exr");
  check_error(merge("--out " + path("x.exr")), "pt_merge", 2, "usage");
  REQUIRE(stage1("--samples 64:16 --seed 9 --out " + path("c.exr")).code == 0);
  r = merge("--out " + path("gap.exr") + " " + path("m.exr") + " " + path("c.exr"));
  CHECK(r.code == 0);
  CHECK(r.err.find("samples 48:16 are in no part") != std::string::npos);
  CHECK(pt::format_ranges(pt::read_film_part(path("gap.exr")).ranges) == "0:48,64:16");
}

TEST_CASE("cli: a part cut by Ctrl-C holds the samples it did and merges with the rest",
          "[stage1][cli][parts][interrupt]") {
  const std::string cut = path("cut.exr"), err = path("cut.stderr"), log = path("cut.stdout");
  fs::remove(cut);
  pid_t pid = ::fork();
  if (pid == 0) {
    std::freopen(err.c_str(), "w", stderr);
    std::freopen(log.c_str(), "w", stdout);
    ::execl(PT_STAGE1_BIN, PT_STAGE1_BIN, "--backend", "cpu", "--width", "64", "--height", "64", "--samples",
            "0:4000000", "--out", cut.c_str(), (char*)nullptr);
    ::_exit(127);
  }
  wait_for_handler(pid, PT_STAGE1_BIN, SIGINT);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ::kill(pid, SIGINT);
  int status = 0;
  ::waitpid(pid, &status, 0);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 130);
  const pt::FilmPart part = pt::read_film_part(cut);
  REQUIRE(part.ranges.size() == 1);
  const std::uint64_t done = part.ranges[0].count;
  CHECK(part.ranges[0].first == 0);
  CHECK(done == part.film.spp());
  CHECK(done > 0);
  // The rest of a longer render from where it stopped: together, one range with no gap.
  REQUIRE(run_program(PT_STAGE1_BIN, "--backend cpu --width 64 --height 64 --samples " + std::to_string(done) +
                                         ":16 --out " + path("rest.exr"),
                      "", scratch())
              .code == 0);
  Run r = merge("--out " + path("whole.exr") + " " + cut + " " + path("rest.exr"));
  INFO(r.err);
  CHECK(r.code == 0);
  CHECK(r.err.empty());
  CHECK(r.out.find(std::to_string(done + 16) + " spp, samples 0:" + std::to_string(done + 16)) != std::string::npos);
}
