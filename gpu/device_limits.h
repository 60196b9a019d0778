// The sizes of the GPU backend's buffers against a Vulkan device's limits and memory, checked
// before anything is built or allocated, so that a scene or image too large for the device
// ends with one line that says so (exit 4) rather than a failed allocation.
// Not part of the article: machinery of the Vulkan backend (gpu_backend.cpp).
#pragma once

#include <cstdint>

#include "common/kernel/scene_types.h"
#include "gpu/vulkan_context.h"

namespace pt {
struct Scene;
struct Bvh;
}  // namespace pt

namespace pt::gpu {

// Throws Error(kExitNoDevice) when `bytes` cannot be one storage buffer of the device (its
// maxStorageBufferRange, or its memory); `what` begins the message ("the textures need").
void check_range(const VulkanContext& context, VkDeviceSize bytes, const char* what);
// Throws Error(kExitNoDevice) when `bytes` are more uvec4 texels than one texel buffer holds.
void check_texels(const VulkanContext& context, VkDeviceSize bytes, const char* what);
// Every buffer that set_scene() and run_pass() will make for this scene, BVH and image, as
// they check them, and all of them together against the device's memory.
void check_scene_memory(const VulkanContext& context, const Scene& scene, uint features, std::uint64_t pixels,
                        const Bvh* bvh);

}  // namespace pt::gpu
