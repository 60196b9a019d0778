// The memory probe and a render's memory need (common/render/memory.h): each limit read from
// a fake machine's files (cgroup v1 and v2, MemAvailable, RLIMIT_AS), the estimate an upper
// bound of the peaks measured. An allocation that fails: test_out_of_memory.cpp.
// Not part of the article: the machinery of the stage programs.
#include <catch2/catch.hpp>

#include <sys/resource.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "common/base/error.h"
#include "common/render/memory.h"
#include "common/scene/scene.h"
#include "tests/support/cli_run.h"

namespace fs = std::filesystem;
using pt::AvailableMemory;
using pt::FramePlan;

namespace {

constexpr std::uint64_t kGB = 1000000000ull;

// A fake machine: files under a scratch folder that stands for /.
struct FakeRoot {
  fs::path dir;
  explicit FakeRoot(const std::string& name) : dir(pt_test::scratch_dir("pt_memory") / name) {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  void file(const std::string& path, const std::string& text) const {
    fs::create_directories((dir / path.substr(1)).parent_path());
    std::ofstream(dir / path.substr(1)) << text;
  }
  AvailableMemory probe(std::uint64_t rlimit_as = 0) const { return pt::available_memory(dir.string(), rlimit_as); }
};

std::string meminfo(std::uint64_t available_kb) {
  return "MemTotal:       32000000 kB\nMemFree:         1000000 kB\nMemAvailable:   " +
         std::to_string(available_kb) + " kB\nBuffers:          100000 kB\n";
}

}  // namespace

TEST_CASE("memory probe: MemAvailable of /proc/meminfo, in bytes", "[memory][reliability]") {
  FakeRoot root("meminfo");
  root.file("/proc/meminfo", meminfo(4000000));
  AvailableMemory m = root.probe();
  CHECK(m.bytes == 4000000ull * 1024);
  CHECK(m.bound.find("MemAvailable") != std::string::npos);
}

TEST_CASE("memory probe: a Slurm job's cgroup v2 memory.max less its usage binds, and is named",
          "[memory][reliability]") {
  FakeRoot root("v2");
  root.file("/proc/meminfo", meminfo(20000000));  // 20 GB free on the machine
  root.file("/proc/self/cgroup", "0::/system.slice/slurmstepd.scope/job_42/step_0\n");
  const std::string job = "/sys/fs/cgroup/system.slice/slurmstepd.scope/job_42";
  root.file(job + "/memory.max", "4000000000\n");
  root.file(job + "/memory.current", "3000000000\n");
  // Page cache the cgroup can drop is not counted as used.
  root.file(job + "/memory.stat", "anon 2000000000\nfile 1000000000\ninactive_file 500000000\nactive_file 500000000\n");
  root.file(job + "/step_0/memory.max", "max\n");  // the step itself has no limit of its own
  root.file(job + "/step_0/memory.current", "2900000000\n");
  AvailableMemory m = root.probe();
  CHECK(m.bytes == 4000000000ull - (3000000000ull - 500000000ull));
  CHECK(m.bound.find(job + "/memory.max") != std::string::npos);
  // A limit above the job's, tighter still once its usage is counted, binds instead.
  root.file("/sys/fs/cgroup/system.slice/memory.max", "10000000000\n");
  root.file("/sys/fs/cgroup/system.slice/memory.current", "9800000000\n");
  m = root.probe();
  CHECK(m.bytes == 200000000ull);
  CHECK(m.bound.find("/sys/fs/cgroup/system.slice/memory.max") != std::string::npos);
}

TEST_CASE("memory probe: cgroup v1's memory.limit_in_bytes binds; its 'no limit' value does not",
          "[memory][reliability]") {
  FakeRoot root("v1");
  root.file("/proc/meminfo", meminfo(20000000));
  root.file("/proc/self/cgroup", "12:pids:/slurm/uid_0/job_7\n4:memory:/slurm/uid_0/job_7/step_batch\n0::/\n");
  const std::string job = "/sys/fs/cgroup/memory/slurm/uid_0/job_7";
  root.file(job + "/step_batch/memory.limit_in_bytes", "9223372036854771712\n");
  root.file(job + "/step_batch/memory.usage_in_bytes", "100000000\n");
  root.file(job + "/memory.limit_in_bytes", "2000000000\n");
  root.file(job + "/memory.usage_in_bytes", "1500000000\n");
  root.file(job + "/memory.stat", "cache 600000000\ninactive_file 1\ntotal_inactive_file 300000000\n");
  AvailableMemory m = root.probe();
  CHECK(m.bytes == 2000000000ull - (1500000000ull - 300000000ull));
  CHECK(m.bound.find(job + "/memory.limit_in_bytes") != std::string::npos);
}

TEST_CASE("memory probe: a container's cgroup is found where /proc/self/mountinfo mounts it",
          "[memory][reliability]") {
  FakeRoot root("container");
  root.file("/proc/meminfo", meminfo(20000000));
  root.file("/proc/self/cgroup", "0::/docker/abc\n");
  // The container sees its own cgroup, /docker/abc, mounted at /sys/fs/cgroup.
  root.file("/proc/self/mountinfo",
            "22 1 0:20 / / rw - overlay overlay rw\n"
            "31 22 0:28 /docker/abc /sys/fs/cgroup ro,nosuid - cgroup2 cgroup2 rw,nsdelegate\n");
  root.file("/sys/fs/cgroup/memory.max", "1000000000\n");
  root.file("/sys/fs/cgroup/memory.current", "250000000\n");
  AvailableMemory m = root.probe();
  CHECK(m.bytes == 750000000ull);
  CHECK(m.bound.find("/sys/fs/cgroup/memory.max") != std::string::npos);
}

TEST_CASE("memory probe: RLIMIT_AS less the address space in use (statm) binds, and is named",
          "[memory][reliability][real_memory]") {
  FakeRoot root("rlimit");
  root.file("/proc/meminfo", meminfo(20000000));
  root.file("/proc/self/statm", "25000 3000 1000 10 0 20000 0\n");
  const std::uint64_t page = std::uint64_t(::sysconf(_SC_PAGESIZE));
  AvailableMemory m = root.probe(432000000);
  CHECK(m.bytes == 432000000 - 25000 * page);
  CHECK(m.bound.find("RLIMIT_AS") != std::string::npos);
  // The address space of this very process: less than the limit by what it has.
  struct rlimit none{RLIM_INFINITY, RLIM_INFINITY};
  REQUIRE(::getrlimit(RLIMIT_AS, &none) == 0);
  if (none.rlim_cur == RLIM_INFINITY) {
    m = pt::available_memory("", 1ull << 40);
    CHECK(m.address_space < (1ull << 40));
    CHECK(m.address_space > (1ull << 40) - 64 * kGB);
    CHECK(m.address_space_bound.find("RLIMIT_AS") != std::string::npos);
  }
}

TEST_CASE("memory probe: sources that are absent or do not parse are left out", "[memory][reliability]") {
  FakeRoot root("garbage");
  root.file("/proc/meminfo", "MemTotal: lots\nMemAvailable: 12abc kB\n");
  root.file("/proc/self/cgroup", "garbage without colons\n0::/job\n4:memory\n");
  root.file("/sys/fs/cgroup/job/memory.max", "-5\n");
  root.file("/sys/fs/cgroup/job/memory.current", "99999999999999999999999999\n");
  root.file("/sys/fs/cgroup/memory.max", "");
  root.file("/proc/self/statm", "not a number\n");
  // Nothing usable: the physical memory, said so.
  AvailableMemory m = root.probe();
  CHECK(m.bytes > 0);
  CHECK(m.bound == "the physical memory");
  // The rlimit alone still binds (the address space in use unknown: taken as none).
  m = root.probe(300000000);
  CHECK(m.bytes == 300000000);
  CHECK(m.bound.find("RLIMIT_AS") != std::string::npos);
}

TEST_CASE("memory need: an upper bound of the peaks measured, per pixel and per triangle", "[memory][reliability]") {
  // Measured max RSS less the RSS at the check (stage1 and stage4, builtin:cornell, 4 spp,
  // 1024^2 and 2048^2, /usr/bin/time): CPU .exr 146 bytes a pixel, .png 65; GPU (lavapipe)
  // .exr 124 (stage1), .png 79. The estimate must stay above each.
  const int side = 2048;
  const std::uint64_t px = std::uint64_t(side) * side;
  auto need = [&](bool gpu, const char* out) {
    FramePlan p;
    p.width = p.height = side, p.gpu = gpu, p.out = out;
    return pt::memory_need(p).bytes;
  };
  CHECK(need(false, "a.exr") >= 146 * px);
  CHECK(need(false, "a.png") >= 66 * px);
  CHECK(need(false, "a.hdr") >= 63 * px);
  CHECK(need(true, "a.exr") >= 146 * px + 16 * px);
  CHECK(need(true, "a.png") >= 80 * px);
  // ...and not wildly above them (a render that fits is not refused).
  CHECK(need(false, "a.exr") <= 200 * px);
  CHECK(need(false, "a.png") <= 100 * px);
  // A resumed render holds the checkpoint's film too; --keep-halves two more channels; an
  // error map its own image, after the image.
  FramePlan p;
  p.width = p.height = side, p.out = "a.png";  // the render's step is the peak, not the write's
  const std::uint64_t plain = pt::memory_need(p).bytes;
  p.resuming = true;
  CHECK(pt::memory_need(p).bytes >= plain + 32 * px);
  p.resuming = false, p.out = "a.exr";
  const std::uint64_t exr = pt::memory_need(p).bytes;
  p.keep_halves = true;
  CHECK(pt::memory_need(p).bytes >= exr + 8 * px);
  p.keep_halves = false, p.error_map = "e.exr";
  CHECK(pt::memory_need(p).bytes >= exr);
  // A scene: the BVH and the backend's copies, per triangle (builtin:furnace_mesh, 1.31 M
  // triangles: CPU 144 bytes a triangle, GPU 146 over the 8x8 image's peak).
  pt::Scene scene;
  scene.triangles.resize(1 << 20);
  FramePlan s;
  s.width = s.height = 8, s.scene = &scene;
  CHECK(pt::memory_need(s).bytes >= 144ull * scene.triangles.size());
  s.gpu = true;
  CHECK(pt::memory_need(s).bytes >= 146ull * scene.triangles.size());
  // Sizes whose products overflow saturate instead of wrapping round to a small need.
  FramePlan huge;
  huge.width = huge.height = 65536;
  CHECK(pt::memory_need(huge).bytes > 65536ull * 65536ull * 100);
}

TEST_CASE("memory check: a render that does not fit is refused with the need, what is available and what binds",
          "[memory][reliability]") {
  FakeRoot root("check");
  root.file("/proc/meminfo", meminfo(20000000));
  root.file("/proc/self/cgroup", "0::/job\n");
  root.file("/sys/fs/cgroup/job/memory.max", "200000000\n");
  root.file("/sys/fs/cgroup/job/memory.current", "100000000\n");
  ::setenv("PT_MEMORY_ROOT", root.dir.c_str(), 1);
  FramePlan p;
  p.width = p.height = 1024;  // about 160 MB for an .exr
  std::string message;
  int code = 0;
  try {
    pt::check_memory(p);
  } catch (const pt::Error& e) {
    message = e.what(), code = e.code();
  }
  p.width = p.height = 256;
  CHECK_NOTHROW(pt::check_memory(p));
  ::unsetenv("PT_MEMORY_ROOT");
  INFO(message);
  CHECK(code == pt::kExitBadOption);
  CHECK(message.find("1024x1024") != std::string::npos);
  CHECK(message.find("needs 1") != std::string::npos);
  CHECK(message.find("100 MB is available") != std::string::npos);
  CHECK(message.find("/sys/fs/cgroup/job/memory.max") != std::string::npos);
  CHECK(message.find('\n') == std::string::npos);
}
