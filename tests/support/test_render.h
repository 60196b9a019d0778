// Rendering from tests: the backend under test (pt_tests: the CPU, pt_gpu_tests: Vulkan),
// and seeds that can be shifted all at once (PT_TEST_SEED_OFFSET) to run every statistical
// test over other seeds, as a new statistical test must be before it is trusted.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "common/render/backend.h"
#include "common/render/render.h"
#include "common/scene/scene.h"

namespace pt::gpu {
class DeviceSession;
}

namespace pt::test {

// "cpu" or "gpu"; set by the test executable's main().
extern std::string backend_under_test;

// A new backend of that kind ("cpu" or "gpu"). Every "gpu" backend is made on test_device().
std::unique_ptr<Backend> make_backend(const std::string& kind, const StageKernels& kernels);

// The test program's one Vulkan device (gpu/device_session.h), made on first use, so that
// each kernel is compiled once per feature set, not once per render; release_test_device()
// destroys it (pt_gpu_tests' main, before it reads the validation layer's error count).
std::shared_ptr<gpu::DeviceSession> test_device();
void release_test_device();

// The seed a test uses: base + PT_TEST_SEED_OFFSET (0 when unset).
std::uint32_t test_seed(std::uint32_t base);

RenderSettings settings(int width, int height, std::uint64_t spp, std::uint32_t seed);

// Renders a scene on the backend under test (or the one named).
RenderResult render_on(const std::string& backend, const StageKernels& kernels, const Scene& scene,
                       const RenderSettings& settings, const RenderHooks& hooks = {});
RenderResult render_on_test_backend(const StageKernels& kernels, const Scene& scene, const RenderSettings& settings);

}  // namespace pt::test
