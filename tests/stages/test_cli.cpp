// The programs as users run them (the contract (README.md)): bad input gets one clear line on stderr
// and the contract's exit code (2 option, 3 scene, 4 device, 5 output), and an existing
// output file is never clobbered by a failed run.
#include <catch2/catch.hpp>

#include "tests/support/cli_run.h"

#include "tests/support/child_signals.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <random>
#include <thread>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>

namespace fs = std::filesystem;

namespace test_cli {  // this file's names: the unity build compiles it with others (tests/CMakeLists.txt)

namespace {

using pt_test::Run;
using pt_test::lines;

using pt_test::read_file;

fs::path scratch() { return pt_test::scratch_dir("pt_cli"); }

Run run(const std::string& args, const std::string& env = "") {
  return pt_test::run_program(PT_STAGE1_BIN, args, env, scratch());
}

void check_error(const Run& r, int code, const std::string& words) {
  pt_test::check_error(r, "stage1_raycast", code, words);
}

std::string write(const std::string& name, const std::string& text) {
  fs::path p = scratch() / name;
  std::ofstream(p) << text;
  return p.string();
}

}  // namespace

TEST_CASE("cli: a good render writes the image and prints one summary line", "[stage1][cli]") {
  std::string out = (scratch() / "ok.exr").string();
  Run r = run("--backend cpu --width 32 --height 24 --spp 2 --out " + out);
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(lines(r.out) == 1);
  CHECK(r.out.find("stage1_raycast: backend cpu") == 0);
  CHECK(r.out.find("32x24, 2 spp") != std::string::npos);
  CHECK(fs::file_size(out) > 0);
  // The file records the render: stage, spp, seed, backend.
  auto in = OIIO::ImageInput::open(out);
  REQUIRE(in);
  const OIIO::ImageSpec& spec = in->spec();
  CHECK(spec.width == 32);
  CHECK(spec.height == 24);
  CHECK(spec.get_string_attribute("pt:stage") == "stage1_raycast");
  CHECK(spec.get_string_attribute("pt:spp") == "2");
  CHECK(spec.get_string_attribute("pt:seed") == "0");
  std::string backend(spec.get_string_attribute("pt:backend"));
  INFO("pt:backend = " << backend);
  CHECK(backend.rfind("cpu", 0) == 0);
  std::vector<float> pixels(32 * 24 * 3);
  REQUIRE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, pixels.data()));
  float peak = 0.0f;
  for (float v : pixels) peak = std::max(peak, v);
  CHECK(peak == 17.0f);  // the ceiling light's red radiance, linear in the EXR
}

TEST_CASE("cli: the summary names the scene's features, and the general kernel when forced", "[cli][features]") {
  Run r = run("--backend cpu --width 8 --height 8 --out " + (scratch() / "f.exr").string());
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("[scene: triangles; diffuse; emissive triangles]") != std::string::npos);
  CHECK(r.out.find("[kernel: general") == std::string::npos);
  Run general = run("--backend cpu --width 8 --height 8 --all-features --out " + (scratch() / "g.exr").string());
  REQUIRE(general.code == 0);
  CHECK(general.out.find("[kernel: general, --all-features]") != std::string::npos);
}

TEST_CASE("cli: --accel bvh (the default) says its BVH in the summary, --accel none does not", "[cli][bvh]") {
  Run r = run("--backend cpu --width 8 --height 8 --out " + (scratch() / "b.exr").string());
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find(" B/tri]") != std::string::npos);
  CHECK(r.out.find("[bvh: ") != std::string::npos);
  Run none = run("--backend cpu --width 8 --height 8 --accel none --out " + (scratch() / "n.exr").string());
  REQUIRE(none.code == 0);
  CHECK(none.out.find("[bvh: ") == std::string::npos);
  CHECK(run("--backend cpu --width 8 --height 8 --accel kd --out " + (scratch() / "k.exr").string()).code == 2);
}

TEST_CASE("cli: degenerate triangles are counted, skipped and said once", "[cli][features]") {
  Run r = run("--backend cpu --width 8 --height 8 --scene " PT_TEST_DATA_DIR "/gltf/degenerate.gltf --out " +
              (scratch() / "d.exr").string());
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.err.find("3 degenerate triangle(s) (zero area or non-finite) skipped") != std::string::npos);
}

TEST_CASE("cli: --help lists every option and the built-in scenes", "[cli]") {
  Run r = run("--help");
  CHECK(r.code == 0);
  for (const char* word : {"--scene", "--width", "--height", "--spp", "--seed", "--backend", "--out", "--sky",
                           "builtin:cornell", "cornell", "furnace"}) {
    CHECK(r.out.find(word) != std::string::npos);
  }
}

TEST_CASE("cli: bad options exit 2 with one line", "[cli]") {
  check_error(run("--spp 0"), 2, "--spp");
  check_error(run("--width -3"), 2, "--width");
  check_error(run("--backend fast"), 2, "--backend");
  check_error(run("--sky 1,2"), 2, "--sky");
  check_error(run("--bogus"), 2, "bogus");
  check_error(run("--out picture.jpg"), 2, ".jpg");
  check_error(run("--width 65536 --height 65536 --backend cpu"), 2, "smaller image");
}

TEST_CASE("cli: --threads beyond 1024 exits 2; threads the system refuses leave the render to those it started",
          "[cli]") {
  check_error(run("--backend cpu --threads 100000"), 2, "--threads");
#ifndef __SANITIZE_ADDRESS__  // AddressSanitizer cannot start under a 1.2 GB address-space limit
  // 1,024 threads of 8 MB stacks do not fit into 1.2 GB of address space: before the fix the
  // pool's failed thread ended the program (std::terminate, exit 134).
  std::string out = (scratch() / "threads.png").string();
  Run r = run("--backend cpu --threads 1024 --width 1 --height 4096 --spp 1 --out " + out, "prlimit --as=1200000000");
  INFO(r.err);
  CHECK(r.code == 0);
  CHECK(r.err.find("stage1_raycast: the system started only ") != std::string::npos);
  CHECK(r.out.find("(1024 threads)") == std::string::npos);
  CHECK(fs::exists(out));
#endif
}

TEST_CASE("cli: bad scenes exit 3 with one line", "[cli]") {
  check_error(run("--backend cpu --scene /nonexistent/scene.gltf"), 3, "/nonexistent/scene.gltf");
  check_error(run("--backend cpu --scene builtin:nothing"), 3, "builtin:nothing");
  check_error(run("--backend cpu --scene " + write("broken.gltf", "{ this is not json")), 3, "broken.gltf");
  std::string required = R"({"asset":{"version":"2.0"},"extensionsUsed":["KHR_draco_mesh_compression"],
    "extensionsRequired":["KHR_draco_mesh_compression"]})";
  check_error(run("--backend cpu --scene " + write("draco.gltf", required)), 3, "KHR_draco_mesh_compression");
  // 12 bytes of buffer, but an accessor of 3 VEC3 floats (36 bytes).
  std::string past = R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],
    "bufferViews":[{"buffer":0,"byteLength":12}],
    "buffers":[{"byteLength":12,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAA"}]})";
  check_error(run("--backend cpu --scene " + write("past.gltf", past)), 3, "accessors[0]");
}

TEST_CASE("cli: an output that cannot be written exits 5 before rendering", "[cli]") {
  check_error(run("--backend cpu --out /proc/no_such_place/image.png"), 5, "/proc/no_such_place/image.png");
}

TEST_CASE("cli: a failed run leaves an existing output file untouched", "[cli]") {
  std::string out = write("keep.png", "the user's file");
  Run r = run("--backend cpu --scene /nonexistent.gltf --out " + out);
  CHECK(r.code == 3);
  CHECK(read_file(out) == "the user's file");
  r = run("--spp 0 --out " + out);
  CHECK(r.code == 2);
  CHECK(read_file(out) == "the user's file");
  // No temporary files are left beside it either.
  int files = 0;
  for (const auto& e : fs::directory_iterator(fs::path(out).parent_path())) files += e.path().filename().string()[0] == '.';
  CHECK(files == 0);
}

TEST_CASE("cli: without a Vulkan driver, gpu exits 4 and auto falls back to the CPU", "[stage1][cli]") {
  const std::string no_driver = "VK_ICD_FILENAMES=/nonexistent.json VK_DRIVER_FILES=/nonexistent.json";
  check_error(run("--backend gpu --width 8 --height 8 --out " + (scratch() / "gpu.png").string(), no_driver), 4,
              "--backend cpu");
  Run r = run("--backend auto --width 8 --height 8 --out " + (scratch() / "auto.png").string(), no_driver);
  INFO(r.err);
  CHECK(r.code == 0);
  CHECK(r.err.find("falls back to the CPU") != std::string::npos);
  CHECK(r.out.find("backend cpu") != std::string::npos);
}

namespace {
// Starts a long render, sends `signals` signals after `delay_ms`, returns the exit code.
int interrupted_render(const std::string& backend, const std::string& out, int signo, int signals, int delay_ms,
                       const char* size = "64") {
  // The scratch folder is named by the test's pid: name the files before forking.
  std::string err = (scratch() / "interrupted.stderr").string(), log = (scratch() / "interrupted.stdout").string();
  pid_t pid = ::fork();
  if (pid == 0) {
    std::freopen(err.c_str(), "w", stderr);
    std::freopen(log.c_str(), "w", stdout);
    ::execl(PT_STAGE1_BIN, PT_STAGE1_BIN, "--backend", backend.c_str(), "--width", size, "--height", size, "--spp",
            "1000000", "--out", out.c_str(), (char*)nullptr);
    ::_exit(127);
  }
  // On a loaded machine start-up can take longer than any fixed delay: wait until the program
  // has installed its handlers (the signal is in /proc/PID/status SigCgt), then the delay.
  pt_test::wait_for_handler(pid, PT_STAGE1_BIN, signo);
  std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
  for (int i = 0; i < signals; i++) {
    // Signals of one kind do not queue: a second one sent at once would merge with the first.
    if (i > 0) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    ::kill(pid, signo);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}
}  // namespace

TEST_CASE("cli: Ctrl-C or SIGTERM at any moment writes a whole image of the samples done, exit 130 / 143",
          "[cli][interrupt]") {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> delay(0, 1000);  // after the handlers are installed
  for (const char* backend : {"cpu", "gpu"}) {
    for (int i = 0; i < 4; i++) {
      std::string out = (scratch() / ("interrupted_" + std::to_string(i) + ".exr")).string();
      fs::remove(out);
      int signo = i % 2 ? SIGTERM : SIGINT;
      int code = interrupted_render(backend, out, signo, 1, delay(rng));
      if (code == 4) continue;  // no Vulkan device here: the GPU case is not this test's
      INFO(backend << ", signal " << signo);
      CHECK(code == 128 + signo);
      auto in = OIIO::ImageInput::open(out);
      REQUIRE(in);
      std::string spp(in->spec().get_string_attribute("pt:spp"));
      std::string summary = read_file(scratch() / "interrupted.stdout");
      INFO("spp " << spp << ", summary " << summary);
      CHECK(std::stoull(spp) > 0);
      CHECK(std::stoull(spp) < 1000000);
      CHECK(summary.find(", " + spp + " spp,") != std::string::npos);
    }
  }
}

TEST_CASE("cli: a second Ctrl-C exits at once and leaves no half-written file", "[cli][interrupt]") {
  std::string out = write("twice.exr", "the user's old image");
  // A large image, so that the pass in flight is still running at the second Ctrl-C.
  int code = interrupted_render("cpu", out, SIGINT, 2, 600, "1024");
  CHECK(code == 130);
  CHECK(read_file(out) == "the user's old image");  // the old file, whole
  int temporaries = 0;
  for (const auto& e : fs::directory_iterator(fs::path(out).parent_path())) {
    temporaries += e.path().filename().string().find(".twice.exr.tmp") == 0;
  }
  CHECK(temporaries == 0);
}

}  // namespace test_cli
