// The reliability of the stage programs as users run them (docs/reliability.md): resume
// after Ctrl-C equals an uninterrupted render bit for bit; checkpoints of other renders and
// damaged ones are refused with one line, one that cannot be written is said once; a
// program without OpenImageIO's module still writes .exr. Not part of the article: machinery.
#include <catch2/catch.hpp>

#include "tests/support/cli_run.h"
#include "tests/support/stage1_cli.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;
using namespace pt_test::stage1_cli;

namespace test_cli_reliability {  // this file's names: the unity build compiles it with others (tests/CMakeLists.txt)

namespace {

using pt_test::Run;
using pt_test::lines;

// `args` run in a child, sent `signo` delay_ms after `wait_for` appears (when given: the
// first checkpoint proves the signal handlers are installed, however slow the start-up on
// a loaded machine); returns the exit code (-1: killed by the signal).
int interrupted(const std::vector<std::string>& args, int delay_ms, int signo, const std::string& wait_for = "") {
  std::string err = path("interrupted.stderr"), log = path("interrupted.stdout");
  std::vector<char*> argv{const_cast<char*>(PT_STAGE1_BIN)};
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = ::fork();
  if (pid == 0) {
    std::freopen(err.c_str(), "w", stderr);
    std::freopen(log.c_str(), "w", stdout);
    ::execv(PT_STAGE1_BIN, argv.data());
    ::_exit(127);
  }
  int status = 0;
  if (!wait_for.empty()) {
    for (int i = 0; i < 6000 && !fs::exists(wait_for); i++) {
      if (::waitpid(pid, &status, WNOHANG) == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
  ::kill(pid, signo);
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// A small CPU render of stage1; `extra` may change its seed or size.
std::string small(const std::string& extra = "--seed 9 --width 48") {
  return "--backend cpu --threads 2 --height 40 " + extra + " ";
}
const std::string kSmall = small();

}  // namespace

TEST_CASE("cli: Ctrl-C or kill -9 with --checkpoint, then --resume, equals the uninterrupted render bit for bit",
          "[reliability][checkpoint]") {
  const std::string whole = path("whole.exr");
  Run r = run(kSmall + "--spp 3000 --out " + whole);
  REQUIRE(r.code == 0);
  Image expected = read_image(whole);
  REQUIRE(expected.spp == 3000);

  std::mt19937 rng(3);
  // While the 3000 spp render (about 3 s here) is running: Ctrl-C after its first
  // checkpoint, kill -9 at any moment from its start.
  std::uniform_int_distribution<int> delay(0, 1800);
  int resumed_from_checkpoint = 0;
  // Ctrl-C twice, then kill -9 twice: whatever moment the kill hits (a checkpoint being
  // written included), the checkpoint left is the old one or the new one, whole.
  for (int i = 0; i < 4; i++) {
    const bool kill9 = i >= 2;
    const std::string out = path("parted_" + std::to_string(i) + ".exr"), ckpt = out + ".ckpt";
    fs::remove(ckpt);
    fs::remove(out);
    int code = interrupted({"--backend", "cpu", "--threads", "2", "--width", "48", "--height", "40", "--seed", "9",
                            "--spp", "3000", "--checkpoint", kill9 ? "0.000001" : "0.05", "--out", out},
                           delay(rng), kill9 ? SIGKILL : SIGINT, kill9 ? "" : ckpt);
    INFO("attempt " << i << ", exit " << code << ", stderr " << slurp(path("interrupted.stderr")));
    if (code == 0) {  // it ended before the signal
      CHECK(!fs::exists(ckpt));  // a finished render removes its checkpoint
      continue;
    }
    REQUIRE(code == (kill9 ? -1 : 130));
    if (kill9 && !fs::exists(ckpt)) continue;  // killed before its first checkpoint
    REQUIRE(fs::exists(ckpt));
    if (!kill9) {
      Image part = read_image(out);
      CHECK(part.spp > 0);
      CHECK(part.spp < 3000);
    }
    Run resumed = run(kSmall + "--spp 3000 --resume --out " + out);
    INFO(resumed.err);
    REQUIRE(resumed.code == 0);
    Image image = read_image(out);
    CHECK(image.spp == 3000);
    CHECK(image.pixels == expected.pixels);  // every float of the image
    CHECK(!fs::exists(ckpt));
    resumed_from_checkpoint++;
  }
  CHECK(resumed_from_checkpoint > 0);
}

TEST_CASE("cli: --resume of another render, of a damaged or a missing checkpoint exits 2 with one line",
          "[reliability][checkpoint]") {
  const std::string out = path("other.exr"), ckpt = out + ".ckpt";
  // A time budget far below the samples asked for leaves the checkpoint behind.
  Run r = run(kSmall + "--spp 4000000 --time-budget 0.3 --checkpoint 0.01 --out " + out);
  REQUIRE(r.code == 0);
  REQUIRE(fs::exists(ckpt));
  const std::string saved = slurp(ckpt);
  check_error(run(small("--seed 10 --width 48") + "--spp 4000000 --resume --out " + out), 2, "different render");
  check_error(run(kSmall + "--sky 1,1,1 --spp 4000000 --resume --out " + out), 2, "different render");
  check_error(run(kSmall + "--all-features --spp 4000000 --resume --out " + out), 2, "different render");
  check_error(run(small("--seed 9 --width 47") + "--spp 4000000 --resume --out " + out), 2, "48x40");
  check_error(run(kSmall + "--spp 1 --resume --out " + out), 2, "more than --spp 1");
  check_error(run(kSmall + "--spp 10 --resume " + path("nothing.ckpt") + " --out " + out), 2, "does not exist");
  std::ofstream(ckpt, std::ios::binary) << saved.substr(0, saved.size() / 2);
  check_error(run(kSmall + "--spp 4000000 --resume --out " + out), 2, "truncated");
  std::string flipped = saved;
  flipped[saved.size() / 2] ^= 0x10;
  std::ofstream(ckpt, std::ios::binary) << flipped;
  check_error(run(kSmall + "--spp 4000000 --resume --out " + out), 2, "damaged");
  // The refused checkpoint is left as it was, for the user to look at.
  CHECK(slurp(ckpt) == flipped);
  // The right options resume it (from the other path, with --resume PATH).
  const std::string copy = path("copy.ckpt");
  std::ofstream(copy, std::ios::binary) << saved;
  Run resumed = run(kSmall + "--spp 4000000 --time-budget 0.2 --resume " + copy + " --out " + out);
  INFO(resumed.err);
  CHECK(resumed.code == 0);
}

TEST_CASE("cli: a checkpoint that cannot be written is said once and the render goes on", "[reliability][checkpoint]") {
  const std::string out = path("blocked.exr");
  fs::create_directories(out + ".ckpt");  // a folder where the checkpoint should go
  Run r = run(kSmall + "--spp 64 --checkpoint 0.000001 --out " + out);
  INFO(r.err);
  CHECK(r.code == 0);
  CHECK(read_image(out).spp == 64);
  CHECK(lines(r.err) == 1);
  CHECK(r.err.find("cannot write checkpoint") != std::string::npos);
  CHECK(r.err.find("goes on without checkpoints") != std::string::npos);
  CHECK(fs::is_directory(out + ".ckpt"));  // not the program's to remove
  fs::remove_all(out + ".ckpt");
}

TEST_CASE("cli: a program copied away from OpenImageIO's module refuses a .png in one line and writes .exr",
          "[stage1][reliability][image]") {
  const fs::path alone = scratch() / "alone";
  fs::create_directories(alone);
  fs::copy_file(PT_STAGE1_BIN, alone / "stage1_raycast", fs::copy_options::overwrite_existing);
  const std::string program = (alone / "stage1_raycast").string(), common = "--backend cpu --width 4 --height 4 --out ";
  Run png = pt_test::run_program(program, common + path("alone.png"), "", scratch());
  pt_test::check_error(png, "stage1_raycast", 5, "pt_openimageio.so");
  CHECK(!fs::exists(path("alone.png")));
  CHECK(pt_test::run_program(program, common + path("alone.exr"), "", scratch()).code == 0);
}

// ---- Memory (issue 45, item 6): the whole need checked before anything large is made ----

}  // namespace test_cli_reliability
