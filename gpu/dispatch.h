// One dispatch of a stage's kernel on the Vulkan device: recorded into a command buffer
// between two timestamp queries, submitted, and waited for on a fence; a device that hangs
// or is lost ends the render with one line of explanation (exit 4).
// Not part of the article: the machinery of the GPU backend.
#pragma once

#include <cstdint>

#include "gpu/compute_pipeline.h"
#include "gpu/vulkan_context.h"

namespace pt::gpu {

class Dispatcher {
 public:
  explicit Dispatcher(const VulkanContext& context);
  ~Dispatcher();
  Dispatcher(const Dispatcher&) = delete;
  Dispatcher& operator=(const Dispatcher&) = delete;

  // Records and submits one dispatch of `pipeline` over groups_x x groups_y workgroups,
  // waits for it; returns its kernel time in seconds (0 without timestamps). `pass`: the
  // number of the pass it belongs to, from 1 (PT_FAULT=device_lost:pass=N counts them).
  double dispatch(const ComputePipeline& pipeline, uint32_t groups_x, uint32_t groups_y, std::uint64_t pass);

  // Whether the device was lost (VK_ERROR_DEVICE_LOST): then it is not used again.
  bool lost() const { return lost_; }

 private:
  const VulkanContext& context_;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  VkQueryPool queries_ = VK_NULL_HANDLE;
  bool lost_ = false;
};

}  // namespace pt::gpu
