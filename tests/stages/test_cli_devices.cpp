// The stage programs' device failures as users meet them (docs/reliability.md), through
// PT_FAULT (gpu/fault.h): no loader or device, limits too small for the image or the scene,
// a device lost mid-render; each ends with its message, exit 4 or a fallback to the CPU, and
// the samples done written. Not part of the article: the machinery of the stage programs.
#include <catch2/catch.hpp>

#include "tests/support/cli_run.h"
#include "tests/support/stage1_cli.h"

#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
using namespace pt_test::stage1_cli;
using pt_test::Run;

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
