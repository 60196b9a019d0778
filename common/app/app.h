// What a stage's main() is made of (the contract (README.md), "Programs"): read the options,
// load the scene, choose the backend, render, write the image. Each step is one function;
// errors anywhere become one line on stderr and the contract's exit code (run_guarded).
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/app/image_output.h"
#include "common/app/options.h"
#include "common/render/backend.h"
#include "common/render/render.h"
#include "common/scene/scene.h"

namespace pt {

// The two backends a stage program is linked with (cpu/cpu_backend.h, gpu/gpu_backend.h).
struct Backends {
  std::unique_ptr<Backend> (*cpu)(const StageKernels& kernels, unsigned threads);
  // Throws pt::Error(kExitNoDevice) when no usable Vulkan device exists.
  std::unique_ptr<Backend> (*gpu)(const StageKernels& kernels, const std::string& device);
  // The Vulkan devices, listed without making a device or a pipeline (gpu::vulkan_devices):
  // what --backend auto weighs. Throws pt::Error(kExitNoDevice) like gpu. nullptr: auto
  // takes the CPU.
  std::vector<VulkanDevice> (*gpu_devices)() = nullptr;
};

// A stage program: what its command line says about it, its kernel, its backends.
struct Stage {
  StageInfo info;
  StageKernels kernels;
  Backends backends;
};

// Runs body; a pt::Error (or any other exception) becomes "<program>: <message>" on stderr
// and its exit code. An unexpected exception exits with internal_error_code (1 for the
// stages and pt_merge; pt_compare's 1 means "not consistent", so it passes 3).
int run_guarded(const char* program, const std::function<int()>& body, int internal_error_code = 1);

// The options (nothing for --help, which is printed), with Ctrl-C handlers installed and
// the image's memory checked.
std::optional<Options> read_options(int argc, char** argv, const Stage& stage);

// The scene of --scene with its camera chosen (--camera, else the first met, else one that
// frames the bounds), the image's size completed by the camera's aspectRatio, and a word on
// stderr about lights this stage cannot see and about a scene that will render black.
Scene load_stage_scene(Options& options, const Stage& stage);

// --backend cpu, gpu, or auto: the GPU backend on a real GPU (auto_backend_choice), or on
// the device that --device or PT_VULKAN_DEVICE names, whatever its kind; else the CPU. auto
// says on stderr which, and why, in one line; when the GPU backend cannot be made, the CPU.
std::unique_ptr<Backend> choose_backend(const Options& options, const Stage& stage);

// --backend auto without --device or PT_VULKAN_DEVICE: the GPU backend when `devices` hold a
// real GPU (discrete, integrated, or virtual: a real GPU passed through to a virtual machine),
// else the CPU; a device that emulates a GPU on the CPU (lavapipe) runs slower than the
// CPU backend. `why` is what stderr says, e.g. "GPU NVIDIA GeForce RTX 3060 (discrete)".
struct AutoBackendChoice {
  bool gpu;
  std::string why;
};
AutoBackendChoice auto_backend_choice(const std::vector<VulkanDevice>& devices);

// Renders in passes, from a checkpoint with --resume and saving one with --checkpoint. When
// the device fails under --backend auto, the CPU goes on from the samples done (backend
// is then the CPU's).
RenderResult render_frame(std::unique_ptr<Backend>& backend, const Scene& scene, const Options& options,
                          const Stage& stage);

// Writes the image (also the samples done before a device failed), removes a finished
// render's checkpoint, prints the summary line; returns the exit code.
int write_result(const OutputFile& out, const Options& options, const Backend& backend, const Scene& scene,
                 const RenderResult& result, const Stage& stage);

// What the image file records about the render (stage, spp, seed, backend, time).
ImageMetadata image_metadata(const char* stage, const Options& options, const Backend& backend,
                             const RenderResult& result);

// The one summary line: stage, backend and device, size, spp, seconds, samples per second,
// then `tags` (e.g. "[scene: triangles; diffuse; emissive triangles]").
std::string summary_line(const char* stage, const Backend& backend, const RenderResult& result,
                         const std::string& tags = "");

}  // namespace pt
