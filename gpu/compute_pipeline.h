// A compute pipeline made from embedded SPIR-V, with the one descriptor set that
// common/shaders/bindings.glsl declares: bindings 0-3 the scene arrays (storage), 4 the
// per-pass parameters (uniform), 5 the pass output, 6 the event counters, 7 the light
// table (storage).
#pragma once

#include <cstdint>
#include <span>

#include "gpu/buffer.h"

namespace pt::gpu {

constexpr uint32_t kBindingCount = 8;
constexpr uint32_t kParamsBinding = 4;

class ComputePipeline {
 public:
  // `features`: the value of the kernel's specialization constant 0, kSceneFeatures
  // (common/shaders/features.glsl).
  ComputePipeline(const VulkanContext& context, std::span<const uint32_t> spirv, uint32_t features);
  ~ComputePipeline();
  ComputePipeline(const ComputePipeline&) = delete;
  ComputePipeline& operator=(const ComputePipeline&) = delete;

  // Points binding i of the descriptor set at buffers[i].
  void bind_buffers(const Buffer* const (&buffers)[kBindingCount]);
  // Records: bind the pipeline and its set, dispatch groups_x * groups_y workgroups.
  void record_dispatch(VkCommandBuffer cmd, uint32_t groups_x, uint32_t groups_y) const;

 private:
  void release();

  VkDevice device_;
  VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkShaderModule module_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
};

}  // namespace pt::gpu
