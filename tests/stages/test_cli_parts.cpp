// One frame in parts from the command line (the contract (README.md), "Parts, merging and
// comparing"): --samples FIRST:COUNT on a stage, pt_merge on the .exr parts. Bad ranges are
// one line and exit 2; parts split at pass ends merge into the one-run image bit for bit; a
// part cut by Ctrl-C holds the samples it did and merges with the rest; pt_merge refuses a
// part of another render naming the file, and says where samples are missing. It trusts
// nothing it reads: an --out that is one of its parts, a header edited or out of range and
// a damaged film are refused in one line (common/app/film_file.h, pt:checksum).
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <thread>

#include "common/app/exr_file.h"
#include "common/app/film_file.h"
#include "tests/support/child_signals.h"
#include "tests/support/cli_run.h"

namespace fs = std::filesystem;
using namespace pt_test;

namespace test_cli_parts {  // this file's names: the unity build compiles it with others (tests/CMakeLists.txt)

namespace {

fs::path scratch() { return scratch_dir("pt_cli_parts"); }
std::string path(const std::string& name) { return (scratch() / name).string(); }

Run stage1(const std::string& args) {
  return run_program(PT_STAGE1_BIN, "--backend cpu --width 12 --height 10 " + args, "", scratch());
}
Run merge(const std::string& args) { return run_program(PT_MERGE_BIN, args, "", scratch()); }
Run compare(const std::string& args) { return run_program(PT_COMPARE_BIN, args, "", scratch()); }

// Copies the part `from` to `to` (in the scratch folder) with `edit` applied, as a user's
// tool that reads and writes .exr files would: the header or the pixels changed.
std::string edit_part(const std::string& from, const std::string& to, const std::function<void(pt::ExrImage&)>& edit) {
  pt::ExrImage image;
  std::string why;
  REQUIRE(pt::read_exr(path(from), image, why));
  edit(image);
  REQUIRE(pt::write_exr(path(to), image, why));
  return path(to);
}

std::function<void(pt::ExrImage&)> with(const std::string& name, const std::string& value) {
  return [=](pt::ExrImage& image) { image.set_attribute(name, value); };
}

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

TEST_CASE("cli: pt_merge refuses an --out that is one of its parts, under any name, and leaves the part whole",
          "[stage1][cli][parts][reliability]") {
  REQUIRE(stage1("--samples 0:16 --seed 4 --out " + path("in0.exr")).code == 0);
  REQUIRE(stage1("--samples 16:16 --seed 4 --out " + path("in1.exr")).code == 0);
  const std::string before = read_file(path("in0.exr"));
  fs::remove(path("in0_link.exr"));
  fs::create_symlink("in0.exr", path("in0_link.exr"));
  fs::remove(path("in0_hard.exr"));
  fs::create_hard_link(path("in0.exr"), path("in0_hard.exr"));
  fs::create_directories(scratch() / "sub");
  // The same name, another spelling of it, a symbolic link to it and a hard link to it.
  for (const std::string& out : {path("in0.exr"), (scratch() / "sub" / ".." / "in0.exr").string(), path("in0_link.exr"),
                                 path("in0_hard.exr")}) {
    INFO("--out " << out);
    check_error(merge("--out " + out + " " + path("in0.exr") + " " + path("in1.exr")), "pt_merge", 2, "same file");
    check_error(merge("--out " + out + " " + path("in1.exr") + " " + path("in0_link.exr")), "pt_merge", 2, "same file");
  }
  CHECK(read_file(path("in0.exr")) == before);
  CHECK(fs::is_symlink(path("in0_link.exr")));
  // Another file is fine.
  Run r = merge("--out " + path("in01.exr") + " " + path("in0.exr") + " " + path("in1.exr"));
  INFO(r.err);
  CHECK(r.code == 0);
}

TEST_CASE("cli: pt_merge and pt_compare refuse a part whose header was edited or whose film was damaged, in one line "
          "naming the file and the field",
          "[stage1][cli][parts][reliability]") {
  REQUIRE(stage1("--samples 0:32 --seed 5 --out " + path("p32.exr")).code == 0);
  REQUIRE(stage1("--samples 32:16 --seed 5 --out " + path("p48.exr")).code == 0);
  REQUIRE(stage1("--samples 0:1 --seed 5 --out " + path("p1.exr")).code == 0);
  const std::string rest = " " + path("p48.exr");
  // Claims 16 samples where its film holds 32: the merge would be 33% too bright.
  check_error(merge("--out " + path("e.exr") + " " + edit_part("p32.exr", "claims16.exr", with("pt:samples", "0:16")) +
                    " " + path("p48.exr")),
              "pt_merge", 3, "claims16.exr' ");
  // A range whose end overflows 64 bits (today a 0-spp black image), and other malformed numbers.
  for (const char* samples : {"1:18446744073709551615", "18446744073709551615:2", "+0:32", "0:-32", "0:32 ", "0:0",
                              "4294967295:2", "0:16,8:24", "00:32"}) {
    INFO("pt:samples " << samples);
    check_error(merge("--out " + path("e.exr") + " " + path("p1.exr") + " " +
                      edit_part("p32.exr", "samples.exr", with("pt:samples", samples))),
                "pt_merge", 3, "samples.exr' has a damaged pt:samples");
  }
  for (const char* seed : {"5abc", "-5", "+5", "05", "4294967301", " 5", ""}) {
    INFO("pt:seed '" << seed << "'");
    check_error(merge("--out " + path("e.exr") + " " + edit_part("p32.exr", "seed.exr", with("pt:seed", seed)) + rest),
                "pt_merge", 3, "seed.exr' ");
    check_error(merge("--out " + path("e.exr") + " " + path("seed.exr") + rest), "pt_merge", 3, "pt:seed");
  }
  // Another option text, and one bit of one film sum: the checksum no longer matches.
  const std::string options = edit_part("p32.exr", "options.exr", with("pt:options", "12x10, edited"));
  check_error(merge("--out " + path("e.exr") + " " + options + rest), "pt_merge", 3, "options.exr' ");
  check_error(merge("--out " + path("e.exr") + " " + options + rest), "pt_merge", 3, "pt:checksum");
  const std::string flipped = edit_part("p32.exr", "flipped.exr", [](pt::ExrImage& image) {
    const int c = image.channel("film.G.lo");
    REQUIRE(c >= 0);
    image.pixels[5 * image.channels.size() + std::size_t(c)] ^= 1u;
  });
  check_error(merge("--out " + path("e.exr") + " " + flipped + rest), "pt_merge", 3, "flipped.exr' ");
  check_error(merge("--out " + path("e.exr") + " " + flipped + rest), "pt_merge", 3, "pt:checksum");
  check_error(compare(flipped + " " + path("p32.exr")), "pt_compare", 3, "pt:checksum");
  CHECK_FALSE(fs::exists(path("e.exr")));
  // A part written before parts carried a checksum: merged, with a note that it could not be
  // checked; its header is still checked against what its film's sums allow.
  const std::string old = edit_part("p32.exr", "old.exr", with("pt:checksum", ""));
  Run r = merge("--out " + path("old_merged.exr") + " " + old + rest);
  INFO(r.err);
  CHECK(r.code == 0);
  CHECK(lines(r.err) == 1);
  CHECK(r.err.find("old.exr' has no pt:checksum") != std::string::npos);
  REQUIRE(merge("--out " + path("new_merged.exr") + " " + path("p32.exr") + rest).code == 0);
  CHECK(pt::read_film_part(path("old_merged.exr")).film.sums() == pt::read_film_part(path("new_merged.exr")).film.sums());
  r = compare(old + " " + path("p32.exr"));
  CHECK((r.code == 0 || r.code == 1));
  CHECK(r.err.find("old.exr' has no pt:checksum") != std::string::npos);
  const std::string old16 = edit_part("old.exr", "old16.exr", with("pt:samples", "0:16"));
  check_error(merge("--out " + path("e.exr") + " " + old16 + rest), "pt_merge", 3, "old16.exr' ");
  check_error(merge("--out " + path("e.exr") + " " + old16 + rest), "pt_merge", 3, "pt:samples");
  check_error(compare(old16 + " " + path("p32.exr")), "pt_compare", 3, "pt:samples");
}

}  // namespace test_cli_parts
