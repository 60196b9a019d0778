// The sizes of the GPU backend's buffers against a Vulkan device's limits and memory
// (device_limits.h), checked before anything is allocated. Not part of the article:
// machinery of the Vulkan backend.
#include "gpu/device_limits.h"

#include <algorithm>
#include <string>

#include "common/base/error.h"
#include "common/render/memory.h"
#include "common/scene/bvh.h"
#include "common/scene/environment.h"
#include "common/scene/scene.h"

namespace pt::gpu {

namespace {

std::string megabytes(VkDeviceSize bytes) {
  return memory_size_words(bytes);  // "134 MB", "4.3 GB"
}

}  // namespace

// A storage buffer larger than the device's limit cannot be bound, nor one larger than
// its memory allocated: say so before trying.
void check_range(const VulkanContext& context, VkDeviceSize bytes, const char* what) {
  VkDeviceSize limit = context.properties().limits.maxStorageBufferRange;
  if (bytes > limit) {
    throw Error(kExitNoDevice, std::string(what) + " a " + megabytes(bytes) + " (" + std::to_string(bytes) +
                                   " bytes) buffer but device '" + context.device_name() + "' allows " +
                                   megabytes(limit) + " (" + std::to_string(limit) +
                                   " bytes); render a smaller image or scene, or use --backend cpu");
  }
  if (bytes > context.heap_size()) {
    throw Error(kExitNoDevice, std::string(what) + " " + megabytes(bytes) + " of memory but device '" +
                                   context.device_name() + "' has " + megabytes(context.heap_size()) +
                                   "; render a smaller image or scene, or use --backend cpu");
  }
}

// The kernel reads the BVH's nodes as uvec4 texels (binding 9): a device allows at least
// 65,536 of them per buffer (lavapipe 2^27, as desktop GPUs do).
void check_texels(const VulkanContext& context, VkDeviceSize bytes, const char* what) {
  const VkDeviceSize texels = (bytes + 15) / 16, limit = context.properties().limits.maxTexelBufferElements;
  if (texels > limit) {
    throw Error(kExitNoDevice, std::string(what) + " " + std::to_string(texels) + " texels of 16 bytes but device '" +
                                   context.device_name() + "' reads at most " + std::to_string(limit) +
                                   " from one texel buffer; render a smaller scene, or use --backend cpu");
  }
}

// Before anything is built or allocated (common/render/memory.h): each buffer that
// set_scene() and run_pass() will make against the device's limits, as they check them,
// and all of them together against its memory.
void check_scene_memory(const VulkanContext& context, const Scene& scene, uint features, std::uint64_t pixels,
                        const Bvh* bvh) {
  VkDeviceSize total = 0;
  auto need = [&](std::uint64_t count, std::uint64_t size, const char* what, bool texels = false) {
    VkDeviceSize bytes = 0;
    if (__builtin_mul_overflow(count, size, &bytes)) bytes = ~VkDeviceSize(0);
    check_range(context, bytes, what);
    if (texels) check_texels(context, bytes, what);
    total = std::min(total + bytes, ~VkDeviceSize(0) / 2);
  };
  const bool textured = (features & kFeatureTextures) && uses_textures(scene);
  need(scene.triangles.size(), sizeof(Triangle), "the scene's triangles need");
  need(scene.spheres.size(), sizeof(Sphere), "the scene needs");
  need(scene.materials.size(), sizeof(Material), "the scene needs");
  need(scene.point_lights.size(), sizeof(PointLight), "the scene needs");
  need(scene.lights.size(), sizeof(Light), "the scene needs");
  need(scene.light_alias.size(), sizeof(LightAlias), "the scene needs");
  if (bvh && !bvh->nodes.empty()) {
    need(bvh->nodes.size(), sizeof(BvhNode), "the BVH's nodes need", true);
    need(bvh->indices.size(), sizeof(uint), "the BVH's triangle list needs");
  }
  if (textured) {
    need(scene.triangle_attributes.size(), sizeof(TriangleAttributes), "the vertex attributes need");
    need(scene.texels.size(), sizeof(uint), "the textures need");
  }
  if ((features & kFeatureShadingNormals) && uses_shading_normals(scene))
    need(scene.triangle_shading.size(), sizeof(TriangleShading), "the shading normals need");
  if ((features & kFeatureEnvironment) && scene.environment) {
    need(scene.environment->radiance.size(), sizeof(float), "the environment map needs");
    need(scene.environment->table.size(), sizeof(float), "the environment map's sampling tables need");
  }
  need(pixels, sizeof(glm::vec4), "the image needs");
  if (total > context.heap_size()) {
    throw Error(kExitNoDevice, "the render needs " + megabytes(total) + " of buffers in all but device '" +
                                   context.device_name() + "' has " + megabytes(context.heap_size()) +
                                   "; render a smaller image or scene, or use --backend cpu");
  }
}

}  // namespace pt::gpu
