// A compute pipeline made from embedded SPIR-V, with the one descriptor set that
// gpu/kernel_bindings.glsl declares: bindings 0-3 the scene arrays (storage), 4 the
// per-pass parameters (uniform), 5 the pass output, 6 the event counters, 7 the light
// table (storage), 8 the triangles again as a uniform buffer (used when they fit), 9 the
// BVH's nodes (a uniform texel buffer of uvec4, Buffer::texel_view) and 10 its triangle
// indices (storage; common/scene/bvh.h), 11 to 14 the
// triangles' attributes, the materials' textures, the texture table and the texels
// (storage; common/kernel/texture.glsl), 15 the shading normals, 16 and 17 the environment
// map's radiance and tables (storage; common/kernel/environment.glsl), 18 the light table's
// alias table (storage; common/kernel/lights.glsl pick_light_entry).
#pragma once

#include <cstdint>
#include <memory>
#include <span>

#include "common/kernel/scene_types.h"
#include "gpu/buffer.h"

namespace pt::gpu {

constexpr uint32_t kBindingCount = 19;
constexpr uint32_t kParamsBinding = 4;
constexpr uint32_t kUniformTrianglesBinding = 8;
constexpr uint32_t kBvhNodesBinding = 9;  // a uniform texel buffer

// The buffer for binding 8 and the value of the kernel's constant kUniformTriangles: the
// triangles copied into a uniform buffer if they fit (then `constant` is the capacity on
// this device: its largest uniform buffer, at most 64 KiB, a GPU's constant cache, in
// 48-byte triangles, less one since the kernel declares kUniformTriangles + 1, and the
// buffer is capacity + 1 triangles long, the same for every scene that fits, so that one
// pipeline serves them all); else a one-triangle placeholder and `constant` 0.
struct UniformTriangles {
  Buffer buffer;
  uint32_t constant = 0;
};
UniformTriangles uniform_triangles(const VulkanContext& context, std::span<const Triangle> triangles);

// A stage's kernel compiled by the driver for one feature set: the descriptor set's layout
// (gpu/kernel_bindings.glsl), the pipeline layout, the shader module and the pipeline. On
// lavapipe compiling one takes 0.5-2 s of CPU, most of a short render's time; a
// DeviceSession (device_session.h) keeps them so that each is compiled once per process.
class KernelProgram {
 public:
  // `features`: the value of the kernel's specialization constant 0, kSceneFeatures
  // (common/kernel/features.glsl); `uniform_triangles`: constant 1, kUniformTriangles
  // (gpu/kernel_bindings.glsl), how many triangles binding 8 holds, 0: read binding 0.
  KernelProgram(const VulkanContext& context, std::span<const uint32_t> spirv, uint32_t features,
                uint32_t uniform_triangles = 0);
  ~KernelProgram();
  KernelProgram(const KernelProgram&) = delete;
  KernelProgram& operator=(const KernelProgram&) = delete;

  VkDescriptorSetLayout set_layout() const { return set_layout_; }
  VkPipelineLayout layout() const { return layout_; }
  VkPipeline pipeline() const { return pipeline_; }

 private:
  void release();

  VkDevice device_;
  VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkShaderModule module_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
};

// A compiled kernel with its own descriptor set: what one backend binds its buffers to and
// dispatches. Several may share one KernelProgram, each with its own buffers.
class ComputePipeline {
 public:
  // Compiles a program of its own (see KernelProgram).
  ComputePipeline(const VulkanContext& context, std::span<const uint32_t> spirv, uint32_t features,
                  uint32_t uniform_triangles = 0);
  // Uses one compiled before, on the same device.
  ComputePipeline(const VulkanContext& context, std::shared_ptr<const KernelProgram> program);
  ~ComputePipeline();
  ComputePipeline(const ComputePipeline&) = delete;
  ComputePipeline& operator=(const ComputePipeline&) = delete;

  // Points binding i of the descriptor set at buffers[i].
  void bind_buffers(const Buffer* const (&buffers)[kBindingCount]);
  // Records: bind the pipeline and its set, dispatch groups_x * groups_y workgroups.
  void record_dispatch(VkCommandBuffer cmd, uint32_t groups_x, uint32_t groups_y) const;

 private:
  void allocate_set();

  VkDevice device_;
  std::shared_ptr<const KernelProgram> program_;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
};

}  // namespace pt::gpu
