// The reliability of the stage programs as users run them (docs/reliability.md): resume
// after Ctrl-C equals an uninterrupted render bit for bit; checkpoints of other renders
// and damaged ones are refused with one line; each device failure (through PT_FAULT,
// gpu/fault.h) ends with its message, exit 4 or a fallback to the CPU, and the samples
// done written; image sizes the machine cannot hold are refused with the numbers.
// Not part of the article: the machinery of the stage programs.
#include <catch2/catch.hpp>

#include "tests/support/cli_run.h"

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <OpenImageIO/imageio.h>

namespace fs = std::filesystem;

namespace {

using pt_test::Run;
using pt_test::lines;

std::string slurp(const fs::path& p) { return pt_test::read_file(p); }

fs::path scratch() { return pt_test::scratch_dir("pt_rel_cli"); }

std::string path(const std::string& name) { return (scratch() / name).string(); }

Run run(const std::string& args, const std::string& env = "") {
  return pt_test::run_program(PT_STAGE1_BIN, args, env, scratch());
}

void check_error(const Run& r, int code, const std::string& words) {
  pt_test::check_error(r, "stage1_raycast", code, words);
}

struct Image {
  std::vector<float> pixels;
  std::uint64_t spp = 0;
};

Image read_image(const std::string& file) {
  Image image;
  auto in = OIIO::ImageInput::open(file);
  if (!in) return image;
  const OIIO::ImageSpec& spec = in->spec();
  image.pixels.resize(std::size_t(spec.width) * spec.height * spec.nchannels);
  in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data());
  image.spp = std::stoull(std::string(spec.get_string_attribute("pt:spp", "0")));
  return image;
}

// Whether this machine has a Vulkan device (lavapipe counts); the device tests need one.
bool have_vulkan_device() {
  static int have = -1;
  if (have < 0) have = run("--backend gpu --width 8 --height 8 --out " + path("probe.exr")).code == 0;
  return have == 1;
}

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

TEST_CASE("cli: a missing loader or no device: gpu exits 4 with one line, auto falls back to the CPU",
          "[reliability][devices]") {
  for (const char* fault : {"PT_FAULT=no_loader", "PT_FAULT=no_device"}) {
    INFO(fault);
    const std::string words = std::string(fault).find("loader") != std::string::npos ? "no Vulkan loader" : "no Vulkan device";
    check_error(run("--backend gpu --width 8 --height 8 --out " + path("gpu.png"), fault), 4, words);
    Run r = run("--backend auto --width 8 --height 8 --out " + path("auto.png"), fault);
    INFO(r.err);
    CHECK(r.code == 0);
    CHECK(r.err.find(words) != std::string::npos);
    CHECK(r.err.find("falls back to the CPU") != std::string::npos);
    CHECK(r.out.find("backend cpu") != std::string::npos);
  }
  check_error(run("--backend gpu --width 8 --height 8 --out " + path("gpu.png"), "PT_FAULT=bogus"), 2, "PT_FAULT");
}

TEST_CASE("cli: a device whose limits cannot hold the image is refused before allocating, with the numbers",
          "[reliability][devices]") {
  if (!have_vulkan_device()) SUCCEED("no Vulkan device here: nothing to test");
  if (!have_vulkan_device()) return;
  // 128 x 128 x 16 bytes = 262144 bytes of pass output; small_limits allows 65536.
  Run r = run("--backend gpu --width 128 --height 128 --out " + path("big.png"), "PT_FAULT=small_limits");
  check_error(r, 4, "262144 bytes");
  CHECK(r.err.find("65536 bytes") != std::string::npos);
  CHECK(!fs::exists(path("big.png")));
  // auto takes the device only when it is a real GPU or named (--device 0): lavapipe is named here.
  r = run("--backend auto --device 0 --width 128 --height 128 --out " + path("big.png"), "PT_FAULT=small_limits");
  INFO(r.err);
  CHECK(r.code == 0);
  CHECK(r.err.find("falls back to the CPU") != std::string::npos);
  CHECK(read_image(path("big.png")).spp == 1);
  // An image within the limits renders on the device.
  r = run("--backend gpu --width 16 --height 16 --out " + path("small.png"), "PT_FAULT=small_limits");
  CHECK(r.code == 0);
  CHECK(r.out.find("backend gpu") != std::string::npos);
}

TEST_CASE("cli: a scene larger than the device's storage-buffer range is refused with exit 4 and the numbers",
          "[reliability][devices][bvh][large]") {
  if (!have_vulkan_device()) SUCCEED("no Vulkan device here: nothing to test");
  if (!have_vulkan_device()) return;
  // builtin:furnace_mesh: 1,310,720 triangles of 48 bytes; small_limits allows 65536 bytes.
  Run r = run("--backend gpu --scene builtin:furnace_mesh --width 4 --height 4 --out " + path("mesh.png"),
              "PT_FAULT=small_limits");
  check_error(r, 4, "the scene's triangles need");
  CHECK(r.err.find("62914560 bytes") != std::string::npos);
  CHECK(r.err.find("65536 bytes") != std::string::npos);
  CHECK(!fs::exists(path("mesh.png")));
}

TEST_CASE("cli: a scene whose BVH has more nodes than the device reads from a texel buffer is refused with exit "
          "4 and the numbers",
          "[reliability][devices][bvh][large]") {
  if (!have_vulkan_device()) SUCCEED("no Vulkan device here: nothing to test");
  if (!have_vulkan_device()) return;
  // builtin:furnace_mesh: 1,310,720 triangles, a BVH of 1,527,829 nodes of two 16-byte texels each
  // (48.8 MB, within lavapipe's storage range); small_texel_limit allows 65536, the Vulkan minimum.
  Run r = run("--backend gpu --scene builtin:furnace_mesh --width 4 --height 4 --out " + path("mesh.png"),
              "PT_FAULT=small_texel_limit");
  check_error(r, 4, "the BVH's nodes need ");
  CHECK(r.err.find(" texels of 16 bytes but device") != std::string::npos);
  CHECK(r.err.find("reads at most 65536 from one texel buffer") != std::string::npos);
  CHECK(!fs::exists(path("mesh.png")));
  // A scene within the limit renders on the device.
  r = run("--backend gpu --scene builtin:cornell --width 8 --height 8 --out " + path("box.png"),
          "PT_FAULT=small_texel_limit");
  CHECK(r.code == 0);
  CHECK(r.out.find("backend gpu") != std::string::npos);
}

TEST_CASE("cli: a device lost mid-render is not retried: gpu writes the samples done and exits 4, auto finishes "
          "on the CPU",
          "[reliability][devices]") {
  if (!have_vulkan_device()) SUCCEED("no Vulkan device here: nothing to test");
  if (!have_vulkan_device()) return;
  // Passes of 1, 1, 2, 4, ... samples: the device is lost in pass 3, after 1 + 1 spp.
  const std::string gpu_out = path("lost.exr");
  Run r = run("--backend gpu --width 16 --height 16 --spp 64 --out " + gpu_out, "PT_FAULT=device_lost:pass=3");
  check_error(r, 4, "VK_ERROR_DEVICE_LOST");
  CHECK(r.err.find("not retried") != std::string::npos);
  CHECK(r.err.find("the 2 spp done are in") != std::string::npos);
  CHECK(read_image(gpu_out).spp == 2);
  // Lost in the first pass: nothing to write, and an older file stays as it was.
  std::ofstream(gpu_out) << "old";
  r = run("--backend gpu --width 16 --height 16 --spp 64 --out " + gpu_out, "PT_FAULT=device_lost:pass=1");
  check_error(r, 4, "nothing was rendered");
  CHECK(slurp(gpu_out) == "old");
  // auto on the device named (--device 0, lavapipe here): the CPU goes on from the samples done.
  const std::string auto_out = path("lost_auto.exr");
  r = run("--backend auto --device 0 --width 16 --height 16 --spp 64 --out " + auto_out, "PT_FAULT=device_lost:pass=3");
  INFO(r.err);
  CHECK(r.code == 0);
  CHECK(r.err.find("falls back to the CPU and goes on from the 2 spp done") != std::string::npos);
  CHECK(read_image(auto_out).spp == 64);
  CHECK(r.out.find("64 spp") != std::string::npos);
}

TEST_CASE("cli: an image larger than the machine can hold is refused with the numbers, exit 2",
          "[reliability][bounds]") {
  // 2^32 pixels: past what one image may have.
  check_error(run("--backend cpu --width 65536 --height 65536 --out " + path("huge.png")), 2, "65536x65536");
  // 40000 x 40000 pixels need about 96 GB of film and buffers: more than a test machine has.
  Run r = run("--backend cpu --width 40000 --height 40000 --out " + path("huge.png"));
  check_error(r, 2, "GB");
  CHECK(r.err.find("40000x40000") != std::string::npos);
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
