// The stage programs' memory bounds as users meet them (docs/reliability.md, issue 45 item
// 6): an image or a render larger than the machine, ulimit -v, a Slurm job's cgroup or the
// device can hold is refused with the numbers before anything large is made (its peak
// memory measured). Not part of the article: the machinery of the stage programs.
#include <catch2/catch.hpp>

#include "tests/support/cli_run.h"
#include "tests/support/stage1_cli.h"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;
using namespace pt_test::stage1_cli;
using pt_test::Run;
using pt_test::lines;

TEST_CASE("cli: an image larger than the machine can hold is refused with the numbers, exit 2",
          "[reliability][bounds]") {
  // 2^32 pixels: past what one image may have.
  check_error(run("--backend cpu --width 65536 --height 65536 --out " + path("huge.png")), 2, "65536x65536");
  // 40000 x 40000 pixels need about 96 GB of film and buffers: more than a test machine has.
  Run r = run("--backend cpu --width 40000 --height 40000 --out " + path("huge.png"));
  check_error(r, 2, "GB");
  CHECK(r.err.find("40000x40000") != std::string::npos);
}

namespace test_cli_memory {  // this file's names: the unity build compiles it with others (tests/CMakeLists.txt)

namespace {

// stage1 run with `args` (and the environment assignments `env`) in a child of its own: its
// exit code, stderr and peak resident memory (wait4's ru_maxrss, kB). Its data may not grow
// past 4 GB (RLIMIT_DATA, which the memory probe does not read): a safety net for the runs
// on a fake machine.
struct PeakRun {
  int code = -1;
  std::string err;
  long max_rss_kb = 0;
};
PeakRun peak_run(const std::vector<std::string>& args, const std::vector<std::pair<std::string, std::string>>& env = {}) {
  const std::string err = path("peak.stderr");
  std::vector<char*> argv{const_cast<char*>(PT_STAGE1_BIN)};
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = ::fork();
  if (pid == 0) {
    for (const auto& [name, value] : env) ::setenv(name.c_str(), value.c_str(), 1);
    struct rlimit data{};
    data.rlim_cur = data.rlim_max = rlim_t(4) << 30;
    ::setrlimit(RLIMIT_DATA, &data);
    if (!std::freopen(err.c_str(), "w", stderr) || !std::freopen("/dev/null", "w", stdout)) ::_exit(125);
    ::execv(PT_STAGE1_BIN, argv.data());
    ::_exit(127);
  }
  int status = 0;
  struct rusage usage{};
  PeakRun r;
  if (::wait4(pid, &status, 0, &usage) != pid) return r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.err = slurp(err);
  r.max_rss_kb = usage.ru_maxrss;
  return r;
}

// A fake machine for the memory probe (PT_MEMORY_ROOT, common/render/memory.h): plenty of
// memory, in a cgroup of `limit` bytes of which `current` are in use (v2, or v1's files).
std::string fake_machine(const std::string& name, std::uint64_t limit, std::uint64_t current, bool v1 = false) {
  const fs::path root = scratch() / name;
  fs::remove_all(root);
  auto write = [&](const std::string& file, const std::string& text) {
    fs::create_directories((root / file).parent_path());
    std::ofstream(root / file) << text;
  };
  write("proc/meminfo", "MemTotal: 1000000000 kB\nMemAvailable: 900000000 kB\n");
  write("proc/self/cgroup", v1 ? "4:memory:/slurm/job_1\n" : "0::/slurm/job_1\n");
  const std::string dir = v1 ? "sys/fs/cgroup/memory/slurm/job_1/" : "sys/fs/cgroup/slurm/job_1/";
  write(dir + (v1 ? "memory.limit_in_bytes" : "memory.max"), std::to_string(limit) + "\n");
  write(dir + (v1 ? "memory.usage_in_bytes" : "memory.current"), std::to_string(current) + "\n");
  return root.string();
}

}  // namespace

TEST_CASE("cli: a render that cannot fit under ulimit -v (RLIMIT_AS) is refused before it renders, never at the "
          "write as a permissions problem",
          "[reliability][bounds][memory][real_memory]") {
  // The case: 2048 x 2048 under 432 MB of address space rendered, then failed to
  // write with "std::bad_alloc ... fix the folder's permissions".
  const std::string out = path("as_limited.exr");
  fs::remove(out);
  Run r = pt_test::run_program("prlimit --as=432000000 " PT_STAGE1_BIN,
                               "--backend cpu --width 2048 --height 2048 --out " + out, "", scratch());
  check_error(r, 2, "RLIMIT_AS");
  CHECK(r.err.find("2048x2048") != std::string::npos);
  CHECK(r.err.find("needs ") != std::string::npos);
  CHECK(r.err.find("available") != std::string::npos);
  CHECK(r.err.find("permissions") == std::string::npos);
  CHECK(r.out.empty());  // no summary line: nothing was rendered
  CHECK(!fs::exists(out));
  // A render that fits under the same limit runs.
  r = pt_test::run_program("prlimit --as=432000000 " PT_STAGE1_BIN, "--backend cpu --width 256 --height 256 --out " + out,
                           "", scratch());
  INFO(r.err);
  CHECK(r.code == 0);
  CHECK(fs::exists(out));
}

TEST_CASE("cli: a Slurm job's cgroup memory limit (v2 memory.max, v1 memory.limit_in_bytes) refuses a render larger "
          "than what the job has left, naming the limit",
          "[reliability][bounds][memory]") {
  const std::string out = path("cgroup.exr");
  for (bool v1 : {false, true}) {
    INFO((v1 ? "cgroup v1" : "cgroup v2"));
    fs::remove(out);
    // 1 GB limit, 950 MB in use: 50 MB left, less than a 1024 x 1024 render's 160 MB.
    const std::string root = fake_machine(v1 ? "job_v1" : "job_v2", 1000000000, 950000000, v1);
    Run r = run("--backend cpu --width 1024 --height 1024 --out " + out, "PT_MEMORY_ROOT=" + root);
    check_error(r, 2, v1 ? "memory.limit_in_bytes" : "memory.max");
    CHECK(r.err.find("50 MB is available") != std::string::npos);
    CHECK(!fs::exists(out));
    // With 500 MB left the same render runs.
    r = run("--backend cpu --width 1024 --height 1024 --out " + out,
            "PT_MEMORY_ROOT=" + fake_machine(v1 ? "job_v1" : "job_v2", 1000000000, 500000000, v1));
    INFO(r.err);
    CHECK(r.code == 0);
  }
}

TEST_CASE("cli: a device that cannot hold the image is refused before the film is allocated",
          "[reliability][devices][memory][real_memory]") {
  if (!have_vulkan_device()) SUCCEED("no Vulkan device here: nothing to test");
  if (!have_vulkan_device()) return;
  // 4096 x 4096: a 268 MB output buffer against small_limits' 64 KiB, and a film of 537 MB
  // that was allocated (and a BVH built) before the refusal.
  PeakRun r = peak_run({"--backend", "gpu", "--width", "4096", "--height", "4096", "--out", path("device.exr")},
                       {{"PT_FAULT", "small_limits"}});
  INFO(r.err);
  CHECK(r.code == 4);
  CHECK(lines(r.err) == 1);
  CHECK(r.err.find("268435456 bytes") != std::string::npos);
  CHECK(r.max_rss_kb < 400 * 1024);  // lavapipe's start-up, not the film's 537 MB
  CHECK(!fs::exists(path("device.exr")));
}

TEST_CASE("cli: --backend gpu at 16384 x 16384 is refused before it allocates or renders",
          "[reliability][memory][real_memory]") {
  if (!have_vulkan_device()) SUCCEED("no Vulkan device here: nothing to test");
  if (!have_vulkan_device()) return;
  // Reported: 84 s and 12.7 GB before the device's refusal. Now the host's memory (exit 2)
  // or the device's limits (exit 4) refuse it first, whichever is smaller.
  PeakRun r = peak_run({"--backend", "gpu", "--width", "16384", "--height", "16384", "--out", path("huge_gpu.exr")});
  INFO(r.err);
  CHECK((r.code == 2 || r.code == 4));
  CHECK(lines(r.err) == 1);
  CHECK(r.max_rss_kb < 1024 * 1024);
  // On a machine with the memory, the device's limit (a storage buffer of 4294967296 bytes
  // is past any device's, whose limit is a 32-bit number): a fake machine of 1 PB shows it.
  r = peak_run({"--backend", "gpu", "--width", "16384", "--height", "16384", "--out", path("huge_gpu.exr")},
               {{"PT_MEMORY_ROOT", fake_machine("petabyte", 1000000000000000, 0)}});
  INFO(r.err);
  CHECK(r.code == 4);
  CHECK(r.err.find("the image needs") != std::string::npos);
  CHECK(r.err.find("4294967296 bytes") != std::string::npos);
  CHECK(lines(r.err) == 1);
  CHECK(r.max_rss_kb < 1024 * 1024);
  CHECK(!fs::exists(path("huge_gpu.exr")));
}

}  // namespace test_cli_memory
