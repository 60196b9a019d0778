// Whether a render's buffers fit the Vulkan device, checked before they are made: one
// storage buffer against the device's range and heap, the BVH's texel buffer against its
// texel limit, and all of a render's buffers together against its memory.
// Not part of the article: the machinery of the GPU backend.
#pragma once

#include <cstdint>
#include <string>

#include "gpu/vulkan_context.h"

namespace pt {
struct Scene;
struct Bvh;
}  // namespace pt

namespace pt::gpu {

// A size in words: "134 MB", "4.3 GB".
std::string megabytes(VkDeviceSize bytes);

// A storage buffer larger than the device's limit cannot be bound, nor one larger than
// its memory allocated: throws pt::Error(kExitNoDevice), naming `what` ("the BVH's nodes
// need"), before anything tries.
void check_range(const VulkanContext& context, VkDeviceSize bytes, const char* what);

// The kernel reads the BVH's nodes as uvec4 texels (binding 9): a device allows at least
// 65,536 of them per buffer (lavapipe 2^27, as desktop GPUs do). Throws as check_range.
void check_texels(const VulkanContext& context, VkDeviceSize bytes, const char* what);

// Each buffer that the backend's set_scene() and run_pass() will make for this scene,
// kernel `features` and image of `pixels`, against the device's limits as they check
// them, and all of them together against its memory (common/render/memory.h,
// DeviceMemoryLimits). Throws as check_range.
void check_render_memory(const VulkanContext& context, const Scene& scene, std::uint32_t features,
                         std::uint64_t pixels, const Bvh* bvh);

}  // namespace pt::gpu
