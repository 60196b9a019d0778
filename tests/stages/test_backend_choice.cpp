// --backend auto (the contract (README.md), "Options"; common/app/app.cpp, choose_backend):
// the GPU backend on a real GPU (discrete, integrated or virtual), or on the device that
// --device or PT_VULKAN_DEVICE names, whatever its kind; else the CPU, since a device that
// emulates a GPU on the CPU (Mesa's lavapipe) is slower than the CPU backend. One line on
// stderr says which and why. --backend gpu takes the best device, lavapipe included.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "common/app/app.h"
#include "common/base/error.h"
#include "gpu/gpu_backend.h"
#include "tests/support/cli_run.h"

namespace fs = std::filesystem;

namespace test_backend_choice {  // this file's names: the unity build compiles it with others (tests/CMakeLists.txt)

namespace {

using Type = pt::VulkanDevice::Type;
using pt_test::Run;

fs::path scratch() { return pt_test::scratch_dir("pt_backend_choice"); }
std::string path(const std::string& name) { return (scratch() / name).string(); }

// stage1 with `env` in front, and without the caller's PT_VULKAN_DEVICE.
Run stage1(const std::string& args, const std::string& env = "") {
  return pt_test::run_program(PT_STAGE1_BIN, "--width 8 --height 8 " + args + " --out " + path("out.png"),
                              "env -u PT_VULKAN_DEVICE " + env, scratch());
}

// This machine's Vulkan devices; empty when there is no loader, driver or device.
std::vector<pt::VulkanDevice> devices_here() {
  try {
    return pt::gpu::vulkan_devices();
  } catch (const pt::Error&) {
    return {};
  }
}

bool has_real_gpu(const std::vector<pt::VulkanDevice>& devices) {
  for (const pt::VulkanDevice& d : devices) {
    if (d.type == Type::discrete || d.type == Type::integrated || d.type == Type::virtual_gpu) return true;
  }
  return false;
}

const std::string kLavapipe = "llvmpipe (LLVM 15.0.6, 256 bits)";

}  // namespace

TEST_CASE("backend auto: a real GPU is chosen over a CPU-emulated device, the best kind first", "[cli][backend]") {
  pt::AutoBackendChoice c = pt::auto_backend_choice({{kLavapipe, Type::cpu}, {"NVIDIA GeForce RTX 3060", Type::discrete}});
  CHECK(c.gpu);
  CHECK(c.why == "GPU NVIDIA GeForce RTX 3060 (discrete)");
  c = pt::auto_backend_choice({{"Intel(R) UHD Graphics 620", Type::integrated}});
  CHECK(c.gpu);
  CHECK(c.why == "GPU Intel(R) UHD Graphics 620 (integrated)");
  // A virtual GPU is a real GPU passed through to a virtual machine.
  c = pt::auto_backend_choice({{kLavapipe, Type::cpu}, {"Virtio-GPU Venus", Type::virtual_gpu}});
  CHECK(c.gpu);
  CHECK(c.why == "GPU Virtio-GPU Venus (virtual)");
  // The one VulkanContext takes without --device: discrete before integrated before virtual.
  c = pt::auto_backend_choice({{"virt", Type::virtual_gpu}, {"igpu", Type::integrated}, {"dgpu", Type::discrete}});
  CHECK(c.why == "GPU dgpu (discrete)");
  c = pt::auto_backend_choice({{"virt", Type::virtual_gpu}, {"igpu", Type::integrated}, {kLavapipe, Type::cpu}});
  CHECK(c.why == "GPU igpu (integrated)");
}

TEST_CASE("backend auto: without a real GPU the CPU backend, saying why", "[cli][backend]") {
  pt::AutoBackendChoice c = pt::auto_backend_choice({{kLavapipe, Type::cpu}});
  CHECK_FALSE(c.gpu);
  CHECK(c.why == "CPU (the only Vulkan device, " + kLavapipe + ", emulates a GPU on the CPU; --backend gpu uses it)");
  c = pt::auto_backend_choice({});
  CHECK_FALSE(c.gpu);
  CHECK(c.why == "CPU (no Vulkan device found)");
  c = pt::auto_backend_choice({{"odd", Type::other}});
  CHECK_FALSE(c.gpu);
  CHECK(c.why.find("odd, is no known kind of GPU") != std::string::npos);
  c = pt::auto_backend_choice({{kLavapipe, Type::cpu}, {"SwiftShader Device", Type::cpu}});
  CHECK_FALSE(c.gpu);
  CHECK(c.why.find("0 " + kLavapipe + " emulates a GPU on the CPU, 1 SwiftShader Device emulates") != std::string::npos);
  CHECK(c.why.find("--device N") != std::string::npos);
}

TEST_CASE("backend auto: this machine's devices choose the backend, one line on stderr says which", "[cli][backend]") {
  const std::vector<pt::VulkanDevice> devices = devices_here();
  Run r = stage1("");  // --backend auto is the default
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(pt_test::lines(r.err) == 1);
  if (devices.empty()) {
    CHECK(r.err.find("falls back to the CPU") != std::string::npos);
    CHECK(r.out.find("backend cpu") != std::string::npos);
  } else if (has_real_gpu(devices)) {
    CHECK(r.err.find("stage1_raycast: --backend auto: GPU ") == 0);
    CHECK(r.out.find("backend gpu") != std::string::npos);
  } else {
    // Lavapipe alone (this project's machines): the CPU backend, which is faster.
    CHECK(r.err.find("stage1_raycast: --backend auto: CPU (") == 0);
    CHECK(r.err.find("emulates a GPU on the CPU; --backend gpu uses it") != std::string::npos);
    CHECK(r.out.find("backend cpu") != std::string::npos);
  }
  // --backend cpu and gpu say nothing about the choice; gpu takes lavapipe too.
  r = stage1("--backend cpu");
  CHECK(r.code == 0);
  CHECK(r.err.empty());
  if (devices.empty()) return;
  r = stage1("--backend gpu");
  INFO(r.err);
  CHECK(r.code == 0);
  CHECK(r.err.empty());
  CHECK(r.out.find("backend gpu") != std::string::npos);
}

TEST_CASE("backend auto: --device or PT_VULKAN_DEVICE takes the device named, whatever its kind", "[cli][backend]") {
  const std::vector<pt::VulkanDevice> devices = devices_here();
  if (devices.empty()) SUCCEED("no Vulkan device here: nothing to test");
  if (devices.empty()) return;
  const std::string name = devices[0].name;
  Run r = stage1("--device 0");
  INFO(r.err);
  CHECK(r.code == 0);
  CHECK(pt_test::lines(r.err) == 1);
  CHECK(r.err == "stage1_raycast: --backend auto: GPU " + name + ", as --device 0 asks\n");
  CHECK(r.out.find("backend gpu (" + name + ")") != std::string::npos);
  // PT_VULKAN_DEVICE: part of the name, as --device takes it (the first word: no quoting).
  const std::string word = name.substr(0, name.find(' '));
  r = stage1("", "PT_VULKAN_DEVICE=" + word);
  INFO(r.err);
  CHECK(r.code == 0);
  CHECK(r.err.find("--backend auto: GPU ") != std::string::npos);
  CHECK(r.err.find("as PT_VULKAN_DEVICE=" + word + " asks") != std::string::npos);
  CHECK(r.out.find("backend gpu") != std::string::npos);
  // A name that matches nothing: the CPU, with the devices listed.
  r = stage1("--device no-such-device");
  INFO(r.err);
  CHECK(r.code == 0);
  CHECK(r.err.find("no Vulkan device matches 'no-such-device'") != std::string::npos);
  CHECK(r.err.find("falls back to the CPU") != std::string::npos);
  CHECK(r.out.find("backend cpu") != std::string::npos);
}

TEST_CASE("backend auto: no loader or no device, listed cheaply, is said once and the CPU renders",
          "[cli][backend]") {
  for (const char* fault : {"PT_FAULT=no_loader", "PT_FAULT=no_device"}) {
    INFO(fault);
    Run r = stage1("", fault);
    INFO(r.err);
    CHECK(r.code == 0);
    CHECK(pt_test::lines(r.err) == 1);
    CHECK(r.err.find("falls back to the CPU") != std::string::npos);
    CHECK(r.out.find("backend cpu") != std::string::npos);
  }
}

}  // namespace test_backend_choice
