// What a stage's main() is made of: parse, load, render, write (the contract (README.md), "Programs").
// Errors anywhere below become one line on stderr and the contract's exit code.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "common/render/backend.h"
#include "common/app/image_output.h"
#include "common/app/options.h"
#include "common/render/render.h"

namespace pt {

// Creates the Vulkan backend (gpu/gpu_backend.h) or throws pt::Error(kExitNoDevice).
using GpuBackendFactory = std::unique_ptr<Backend> (*)(const StageKernels& kernels, const std::string& device);

// A whole stage program: parse the options, check the output, load the scene, render on
// the chosen backend, write the image, print the summary line. Returns the exit code.
int run_stage(int argc, char** argv, const StageInfo& stage, const StageKernels& kernels,
              GpuBackendFactory make_gpu);

// Runs body; a pt::Error (or any other exception) becomes "<stage>: <message>" on stderr
// and its exit code.
int guarded_main(const char* stage, const std::function<int()>& body);

// --backend cpu, gpu, or auto (gpu when a device exists, else cpu, saying so on stderr).
std::unique_ptr<Backend> make_backend(const Options& options, const StageKernels& kernels,
                                      GpuBackendFactory make_gpu);

RenderSettings render_settings(const Options& options, const char* stage);

// What the image file records about the render (stage, spp, seed, backend, time).
ImageMetadata image_metadata(const char* stage, const Options& options, const Backend& backend,
                             const RenderResult& result);

// The one summary line: stage, backend and device, size, spp, seconds, samples per second,
// then `tags` (e.g. "[scene: triangles; diffuse; emissive triangles]").
std::string summary_line(const char* stage, const Backend& backend, const RenderResult& result,
                         const std::string& tags = "");

}  // namespace pt
