// The two backends behind one interface: the CPU runs a stage's kernel compiled as C++ on
// all cores, the GPU runs the same kernel compiled to SPIR-V (gpu/). A backend renders one
// pass at a time; the film (film.h) adds the passes up.
#pragma once

#include <algorithm>
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
class Backend;

// What a stage's own step before the render found: the values its kernel reads in
// FrameParams::stage_params during the render, and a note for the summary line.
struct StageTuning {
  glm::vec4 params{0.0f};
  std::string note;  // one bracketed phrase for the summary line, or empty
};

// The one hook a stage may provide (stage6_variance_aware: a small render that sets its MIS
// weights): render() calls it on the backend once the scene is set, before the first pass,
// with the render's params and feature bits and a buffer of the image's size that it may
// render smaller passes into. It must be deterministic: a resumed render or a part calls it
// again and must get the same values.
using BeforeRender = StageTuning (*)(Backend& backend, const FrameParams& params, uint features,
                                     std::span<glm::vec4> buffer);

// Everything a stage hands to the backends: its name, and its kernel in both forms.
struct StageKernels {
  const char* name;                      // e.g. "stage1_raycast"
  std::span<const CpuKernel> cpu;        // the integrator compiled as C++, one copy per
                                         // feature variant (cpu/cpu_variants.h); one
                                         // copy alone is the general kernel
  std::span<const std::uint32_t> spirv;  // the same integrator compiled to SPIR-V
  bool uses_light_table = false;         // reads lights[] and point_lights[] (stage4)
  BeforeRender before_render = nullptr;  // the stage's step before the render, if any
};

// A Vulkan device as --backend auto weighs it (common/app/app.h, Backends::gpu_devices):
// its name and its kind, listed by gpu/gpu_backend.h's vulkan_devices without making a
// device or a pipeline. `cpu` is an emulation on the processor, such as Mesa's lavapipe.
struct VulkanDevice {
  enum class Type { discrete, integrated, virtual_gpu, cpu, other };
  std::string name;  // e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  Type type;
};

// "No pixel" in kCounterNonFinitePixel.
constexpr uint kNoPixel = 0xffffffffu;

// What a pass reports besides its image.
struct PassResult {
  double kernel_seconds = 0.0;  // the time the kernel ran (GPU: timestamp queries)
  // The kernel's event counters (scene_types.h): counts that it adds to, and one pixel index
  // that it lowers (atomicMin), kNoPixel while no sample was dropped: non_finite_pixel().
  uint counters[kCounterCount] = {};
  // Set when the backend could not render the pass whole (a GPU driver that cut the kernel's
  // loops short: gpu/loop_limit.h): what happened and what to do, one line. A wrong pass.
  std::string cut_short;

  PassResult() { counters[kCounterNonFinitePixel] = kNoPixel; }
  uint non_finite_pixel() const { return counters[kCounterNonFinitePixel]; }
  // Takes in another part of the same pass (other samples or pixels): times and counts
  // add up, the pixel index is the lower one, and a part cut short cuts the whole.
  void add(const PassResult& part) {
    kernel_seconds += part.kernel_seconds;
    for (uint c = 0; c < kCounterCount; c++) {
      counters[c] = c == kCounterNonFinitePixel ? std::min(counters[c], part.counters[c]) : counters[c] + part.counters[c];
    }
    if (cut_short.empty()) cut_short = part.cut_short;
  }
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
  // render_pixel(): the radiance sum, and the root of the squared luminances' sum in slot
  // kPassRootSumSquares).
  virtual PassResult run_pass(const FrameParams& params, std::span<glm::vec4> out) = 0;
  // The stage's step before the render (StageKernels::before_render), or nullptr.
  virtual BeforeRender before_render() const { return nullptr; }
};

}  // namespace pt
