// An allocation that fails, said as out of memory (common/render/memory.h, common/app/app.h):
// the innermost memory step names what was being allocated, and an .exr whose encoding runs
// out of memory under RLIMIT_AS says so, exit 2, never a folder's permissions.
// Not part of the article: the machinery of the stage programs.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <new>
#include <string>
#include <thread>
#include <vector>

#include "common/app/app.h"
#include "common/app/image_output.h"
#include "common/base/error.h"
#include "common/render/film.h"
#include "common/render/memory.h"
#include "tests/support/cli_run.h"
#include "tests/support/stderr_capture.h"

extern char** environ;

namespace fs = std::filesystem;

namespace {

constexpr std::uint64_t kMiB = 1ull << 20;

// The .exr out-of-memory test's child: the test program run afresh with this tag and
// PT_OOM_EXR_OUT naming the file to write. A fresh process, not a fork of this one: a fork
// of the test process holds none of its threads but all of their state (issue #51: OpenEXR's
// thread pool, which OpenImageIO's readers start, waited for its workers in the child, and
// the test hung).
constexpr const char* kChildTag = "[.oom_exr_child]";
constexpr const char* kChildOut = "PT_OOM_EXR_OUT";

// Waits for `pid` up to `seconds`; a child still running then is killed and reported.
bool wait_or_kill(pid_t pid, int seconds, int& status) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
  while (std::chrono::steady_clock::now() < end) {
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) return true;
    if (done < 0) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ::kill(pid, SIGKILL);
  ::waitpid(pid, &status, 0);
  return false;
}

}  // namespace
TEST_CASE("memory step: the innermost step names what was being allocated, also once an exception has left it",
          "[memory][reliability]") {
  { pt::MemoryStep before("reading the options"); }  // a step ended without an exception leaves none
  CHECK(pt::MemoryStep::current().empty());
  {
    pt::MemoryStep outer("rendering");
    CHECK(pt::MemoryStep::current() == "rendering");
    {
      pt::MemoryStep inner("writing the image 'a.exr'");
      CHECK(pt::MemoryStep::current() == "writing the image 'a.exr'");
    }
    CHECK(pt::MemoryStep::current() == "rendering");
  }
  CHECK(pt::MemoryStep::current().empty());
  pt_test::StderrCapture err;
  int code = pt::run_guarded("stage1_raycast", [] {
    pt::MemoryStep step("building the BVH");
    throw std::bad_alloc();
    return 0;
  });
  const std::string text = err.text();
  CHECK(code == pt::kExitBadOption);
  CHECK(text == "stage1_raycast: out of memory while building the BVH; render a smaller image or scene, or give it "
                "more memory\n");
}

TEST_CASE("memory: an .exr that runs out of memory while it is encoded says out of memory, exit 2, never a "
          "folder's permissions",
          "[memory][reliability][real_memory]") {
  const fs::path dir = pt_test::scratch_dir("pt_memory");
  const std::string out = (dir / "oom.exr").string();
  fs::remove(out);
  const fs::path err_path = dir / "oom.stderr";
  // Everything the child needs is made before it starts: posix_spawn runs nothing of this
  // process's code in the child.
  const std::string exe = fs::read_symlink("/proc/self/exe").string(), tag = kChildTag;
  std::string out_env = std::string(kChildOut) + "=" + out;
  std::vector<char*> argv{const_cast<char*>(exe.c_str()), const_cast<char*>(tag.c_str()), nullptr};
  std::vector<char*> envp{out_env.data()};
  for (char** e = environ; *e; ++e) envp.push_back(*e);
  envp.push_back(nullptr);
  posix_spawn_file_actions_t files;
  ::posix_spawn_file_actions_init(&files);
  ::posix_spawn_file_actions_addopen(&files, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  ::posix_spawn_file_actions_addopen(&files, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  ::posix_spawn_file_actions_addopen(&files, STDERR_FILENO, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  const int spawned = ::posix_spawn(&pid, exe.c_str(), &files, nullptr, argv.data(), envp.data());
  ::posix_spawn_file_actions_destroy(&files);
  REQUIRE(spawned == 0);
  int status = 0;
  const bool ended = wait_or_kill(pid, 600, status);
  const std::string text = pt_test::read_file(err_path);
  INFO(text);
  REQUIRE(ended);  // else killed after 600 s: the child hung
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == pt::kExitBadOption);
  CHECK(pt_test::lines(text) == 1);
  CHECK(text.find("out of memory while writing the image") != std::string::npos);
  CHECK(text.find("permissions") == std::string::npos);
  CHECK(!fs::exists(out));
}

// The child of the test above (hidden: run only by it). It exits with run_guarded's code.
TEST_CASE("memory: the .exr out-of-memory test's child writes its .exr under RLIMIT_AS", "[.oom_exr_child]") {
  const char* out_env = std::getenv(kChildOut);
  if (out_env == nullptr) {
    SUCCEED("run by the .exr out-of-memory test only, which names its file in " << kChildOut);
    return;
  }
  const std::string out = out_env;
  // A film of 1024 x 1024: its .exr's channels take 48 MiB, their encoding as much again; the
  // child may grow by 75 MiB, so the channels are made and their encoding is not.
  const int side = 1024;
  pt::Film film(side, side);
  std::vector<glm::vec4> pass(std::size_t(side) * side, glm::vec4(0.5f, 0.25f, 0.125f, 0.5f));
  film.add_pass(pass, 1);
  film.add_pass(pass, 1);
  const std::vector<float> rgb = film.mean_rgb();
  const pt::OutputFile file(out);
  pt::ImageMetadata meta;
  meta.stage = "stage1_raycast", meta.film = &film, meta.ranges = {{0, 2}};
  std::ifstream statm("/proc/self/statm");
  std::uint64_t pages = 0;
  statm >> pages;
  struct rlimit as{};
  as.rlim_cur = as.rlim_max = rlim_t(pages * std::uint64_t(::sysconf(_SC_PAGESIZE)) + 75 * kMiB);
  ::setrlimit(RLIMIT_AS, &as);
  const int code = pt::run_guarded("stage1_raycast", [&] {
    pt::MemoryStep step("writing the image '" + out + "'");
    file.write(rgb, side, side, meta);
    return 0;
  });
  std::fflush(stderr);
  ::_exit(code);
}
