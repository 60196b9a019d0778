// A Vulkan device and the kernels the driver compiled on it, shared by the backends made
// from it. Not part of the article: machinery of the Vulkan backend (issue #51: on lavapipe
// compiling a kernel for a feature set costs 0.5-2 s of CPU, most of a small render's time,
// and the test programs render hundreds of small images with a few dozen feature sets).
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <tuple>

#include "gpu/compute_pipeline.h"
#include "gpu/vulkan_context.h"

namespace pt::gpu {

class DeviceSession {
 public:
  // device: as VulkanContext takes it ("" for the best device, an index, part of a name).
  explicit DeviceSession(const std::string& device) : context_(device) {}

  const VulkanContext& context() const { return context_; }

  // The kernel `spirv` compiled for (features, uniform_triangles) on this device: compiled
  // on the first call, the same program afterwards. `spirv` must outlive the session (the
  // stages' kernels are static arrays: StageKernels::spirv); it is known by its address.
  std::shared_ptr<const KernelProgram> program(std::span<const uint32_t> spirv, uint32_t features,
                                               uint32_t uniform_triangles);

  // How many programs the driver compiled (tests: a second backend compiles none again).
  std::size_t compiled() const;

 private:
  using Key = std::tuple<const uint32_t*, std::size_t, uint32_t, uint32_t>;
  VulkanContext context_;
  mutable std::mutex mutex_;
  std::map<Key, std::shared_ptr<const KernelProgram>> programs_;
};

}  // namespace pt::gpu
