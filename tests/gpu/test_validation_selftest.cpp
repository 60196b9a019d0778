// The validation-layer check of pt_gpu_tests can fail (docs/reliability.md): a deliberate
// misuse of Vulkan (a buffer of size 0) must be reported by VK_LAYER_KHRONOS_validation and
// counted by the backend's debug messenger (gpu/vulkan_context.cpp). Hidden from normal
// runs; the ctest entry pt_gpu_validation_selftest runs it with PT_VULKAN_VALIDATION=1 and
// passes only if the run ends by reporting the error.
// Not part of the article: the machinery of the GPU backend.
#include <catch2/catch.hpp>

#include <cstdlib>

#include "gpu/vulkan_context.h"

TEST_CASE("validation: a misuse of Vulkan is reported and counted", "[.validation_selftest]") {
  REQUIRE(std::getenv("PT_VULKAN_VALIDATION") != nullptr);
  pt::gpu::VulkanContext context("");
  const int before = pt::gpu::validation_errors();
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = 0;  // VUID-VkBufferCreateInfo-size-00912: size must be greater than 0
  info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer buffer = VK_NULL_HANDLE;
  if (vkCreateBuffer(context.device(), &info, nullptr, &buffer) == VK_SUCCESS && buffer) {
    vkDestroyBuffer(context.device(), buffer, nullptr);
  }
  CHECK(pt::gpu::validation_errors() > before);
}
