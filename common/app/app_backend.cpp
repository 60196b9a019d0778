// choose_backend, the step of a stage's main() that picks --backend (app.h): cpu, gpu, or
// auto, which weighs the Vulkan devices (auto_backend_choice) and falls back to the CPU
// when the GPU backend cannot be made.
// Not part of the article: the machinery of the stage programs.
#include "common/app/app.h"

#include <cstdio>
#include <cstdlib>

#include "common/base/error.h"

namespace pt {

AutoBackendChoice auto_backend_choice(const std::vector<VulkanDevice>& devices) {
  using Type = VulkanDevice::Type;
  // The real GPU that VulkanContext takes without --device: discrete before integrated
  // before virtual, the first of its kind.
  const VulkanDevice* best = nullptr;
  for (Type type : {Type::discrete, Type::integrated, Type::virtual_gpu}) {
    for (const VulkanDevice& d : devices) {
      if (!best && d.type == type) best = &d;
    }
  }
  if (best) {
    const char* kind = best->type == Type::discrete ? "discrete" : best->type == Type::integrated ? "integrated" : "virtual";
    return {true, "GPU " + best->name + " (" + kind + ")"};
  }
  if (devices.empty()) return {false, "CPU (no Vulkan device found)"};
  auto what = [](const VulkanDevice& d) {
    return d.type == Type::cpu ? "emulates a GPU on the CPU" : "is no known kind of GPU";
  };
  if (devices.size() == 1) {
    return {false, "CPU (the only Vulkan device, " + devices[0].name + ", " + what(devices[0]) +
                       "; --backend gpu uses it)"};
  }
  std::string list;
  for (std::size_t i = 0; i < devices.size(); i++) {
    list += (i ? ", " : "") + std::to_string(i) + " " + devices[i].name + " " + what(devices[i]);
  }
  return {false, "CPU (no Vulkan device is a GPU: " + list + "; --backend gpu or --device N uses one)"};
}

std::unique_ptr<Backend> choose_backend(const Options& options, const Stage& stage) {
  const Backends& b = stage.backends;
  if (options.backend == "cpu") return b.cpu(stage.kernels, options.threads);
  if (options.backend == "gpu") return b.gpu(stage.kernels, options.device);
  // auto: a device named by --device or PT_VULKAN_DEVICE is used whatever its kind (lavapipe
  // too); without one, only a real GPU, since lavapipe is slower than the CPU backend.
  const char* name = stage.info.name;
  const char* env = std::getenv("PT_VULKAN_DEVICE");
  const std::string asked = !options.device.empty() ? "as --device " + options.device + " asks"
                            : env && *env          ? std::string("as PT_VULKAN_DEVICE=") + env + " asks"
                                                   : "";
  try {
    std::string why;
    if (asked.empty()) {
      AutoBackendChoice choice = b.gpu_devices ? auto_backend_choice(b.gpu_devices())
                                               : AutoBackendChoice{false, "CPU (this program has no GPU backend)"};
      if (!choice.gpu) {
        std::fprintf(stderr, "%s: --backend auto: %s\n", name, choice.why.c_str());
        return b.cpu(stage.kernels, options.threads);
      }
      why = choice.why;
    }
    std::unique_ptr<Backend> gpu = b.gpu(stage.kernels, options.device);
    if (why.empty()) why = "GPU " + gpu->device_name() + ", " + asked;
    std::fprintf(stderr, "%s: --backend auto: %s\n", name, why.c_str());
    return gpu;
  } catch (const Error& e) {
    if (e.code() != kExitNoDevice) throw;
    std::fprintf(stderr, "%s: %s; --backend auto falls back to the CPU\n", name, e.what());
    return b.cpu(stage.kernels, options.threads);
  }
}

}  // namespace pt
