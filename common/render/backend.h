// The two backends behind one interface: the CPU runs a stage's kernel compiled as C++ on
// all cores, the GPU runs the same kernel compiled to SPIR-V (gpu/). A backend renders one
// pass at a time; the film (film.h) adds the passes up.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include <glm/glm.hpp>

#include "common/kernel/scene_types.h"

namespace pt {

struct Scene;
struct Bvh;
struct CpuKernel;  // a stage's kernel compiled as C++, as the CPU backend calls it (cpu/kernel_scene.h)

// Everything a stage hands to the backends: its name, and its kernel in both forms.
struct StageKernels {
  const char* name;                      // e.g. "stage1_raycast"
  std::span<const CpuKernel> cpu;        // the integrator compiled as C++, one copy per
                                         // feature variant (cpu/cpu_variants.h); one
                                         // copy alone is the general kernel
  std::span<const std::uint32_t> spirv;  // the same integrator compiled to SPIR-V
  bool uses_light_table = false;         // reads lights[] and point_lights[] (stage4)
};

// A Vulkan device as --backend auto weighs it (common/app/app.h, Backends::gpu_devices):
// its name and its kind, listed by gpu/gpu_backend.h's vulkan_devices without making a
// device or a pipeline. `cpu` is an emulation on the processor, such as Mesa's lavapipe.
struct VulkanDevice {
  enum class Type { discrete, integrated, virtual_gpu, cpu, other };
  std::string name;  // e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  Type type;
};

// What a pass reports besides its image.
struct PassResult {
  double kernel_seconds = 0.0;       // the time the kernel ran (GPU: timestamp queries)
  uint counters[kCounterCount] = {};  // the kernel's event counters (scene_types.h)
};

class Backend {
 public:
  virtual ~Backend() = default;
  virtual std::string kind() const = 0;         // "cpu" or "gpu"
  virtual std::string device_name() const = 0;  // e.g. "2 threads", "llvmpipe (LLVM 15.0.6)"
  // Makes the scene's arrays available to the kernel (an upload on the GPU), and readies
  // the kernel specialised to `features` (kFeature* bits, common/kernel/features.glsl):
  // arrays that no feature of the set reads are not uploaded. `bvh`: the hierarchy over the
  // scene's triangles (common/scene/bvh.h), or nullptr to search them all; it outlives
  // the passes that follow (render() owns it).
  virtual void set_scene(const Scene& scene, uint features, const Bvh* bvh) = 0;
  // Renders params.sample_count samples of every pixel into out (width * height values of
  // render_pixel(): rgb sum, squared-luminance sum).
  virtual PassResult run_pass(const FrameParams& params, std::span<glm::vec4> out) = 0;
};

}  // namespace pt
