// main() of pt_gpu_tests: the image tests again, on the Vulkan backend. Where no Vulkan
// device exists it says so and returns 77, which ctest reports as skipped.
#include <cstdio>
#include <string>

#include "common/base/error.h"
#include "gpu/gpu_backend.h"
#include "gpu/vulkan_context.h"
#include "stage1_raycast/kernels.h"
#include "tests/catch_runner.h"
#include "tests/support/test_render.h"

int main(int argc, char** argv) {
  try {
    auto probe = pt::gpu::create_backend(stage1::kernels(), pt::test::test_device());
    std::printf("GPU tests run on '%s'\n", probe->device_name().c_str());
  } catch (const pt::Error& e) {
    // No device: skipped. Validation asked for but its layer missing: a failure to fix.
    bool layer_missing = std::string(e.what()).find("PT_VULKAN_VALIDATION") != std::string::npos;
    std::printf("%s the GPU tests: %s\n", layer_missing ? "cannot run" : "skipping", e.what());
    return layer_missing ? 1 : 77;
  }
  pt::test::backend_under_test = "gpu";
  int failed = pt::test::run_catch(argc, argv);
  pt::test::release_test_device();  // its destruction is checked by the validation layer too
  // PT_VULKAN_VALIDATION=1 (the ctest entry pt_gpu_tests_validation): any error the
  // validation layer reported fails the run.
  if (int errors = pt::gpu::validation_errors()) {
    std::printf("the Vulkan validation layer reported %d error(s) (see stderr)\n", errors);
    return failed ? failed : 1;
  }
  return failed;
}
