// Rendering from tests (see test_render.h).
#include "tests/support/test_render.h"

#include <cstdlib>

#include "cpu/cpu_backend.h"
#include "gpu/device_session.h"
#include "gpu/gpu_backend.h"

namespace pt::test {

std::string backend_under_test = "cpu";

// One Vulkan device for the whole test program, made on first use: every GPU render of the
// tests makes its own backend (buffers, descriptor sets) on it, and a kernel is compiled once
// per feature set rather than once per render (issue #51: the compiles were 87% of the GPU
// tests' CPU time on lavapipe, and half of them compiled a kernel compiled before).
namespace {
std::shared_ptr<gpu::DeviceSession> the_test_device;
}  // namespace

std::shared_ptr<gpu::DeviceSession> test_device() {
  if (!the_test_device) the_test_device = std::make_shared<gpu::DeviceSession>("");
  return the_test_device;
}

void release_test_device() { the_test_device.reset(); }

std::unique_ptr<Backend> make_backend(const std::string& kind, const StageKernels& kernels) {
  if (kind == "gpu") return gpu::create_backend(kernels, test_device());
  return make_cpu_backend(kernels);
}

std::uint32_t test_seed(std::uint32_t base) {
  const char* offset = std::getenv("PT_TEST_SEED_OFFSET");
  return base + (offset ? std::uint32_t(std::strtoul(offset, nullptr, 10)) : 0u);
}

RenderSettings settings(int width, int height, std::uint64_t spp, std::uint32_t seed) {
  RenderSettings s;
  s.width = width;
  s.height = height;
  s.spp = spp;
  s.seed = seed;
  return s;
}

RenderResult render_on(const std::string& backend, const StageKernels& kernels, const Scene& scene,
                       const RenderSettings& settings, const RenderHooks& hooks) {
  std::unique_ptr<Backend> b = make_backend(backend, kernels);
  return render(*b, scene, settings, hooks);
}

RenderResult render_on_test_backend(const StageKernels& kernels, const Scene& scene, const RenderSettings& settings) {
  return render_on(backend_under_test, kernels, scene, settings);
}

}  // namespace pt::test
