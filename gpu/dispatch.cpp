// One dispatch of the kernel (see dispatch.h): the command buffer, the fence and the
// timestamp queries it uses, made once per backend and reused by every dispatch.
// Not part of the article: the machinery of the GPU backend.
#include "gpu/dispatch.h"

#include <string>

#include "common/base/error.h"
#include "gpu/fault.h"

namespace pt::gpu {

namespace {
constexpr uint64_t kFenceTimeoutNs = 120'000'000'000;  // a dispatch that takes 2 minutes is hung
}  // namespace

Dispatcher::Dispatcher(const VulkanContext& context) : context_(context) {
  VkDevice dev = context_.device();
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = context_.command_pool();
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  check(vkAllocateCommandBuffers(dev, &alloc, &cmd_), "allocating a command buffer");
  VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  check(vkCreateFence(dev, &fence_info, nullptr, &fence_), "creating a fence");
  if (context_.has_timestamps()) {
    VkQueryPoolCreateInfo q{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    q.queryType = VK_QUERY_TYPE_TIMESTAMP;
    q.queryCount = 2;
    check(vkCreateQueryPool(dev, &q, nullptr, &queries_), "creating a timestamp query pool");
  }
}

Dispatcher::~Dispatcher() {
  VkDevice dev = context_.device();
  if (queries_) vkDestroyQueryPool(dev, queries_, nullptr);
  if (fence_) vkDestroyFence(dev, fence_, nullptr);
}

// [excerpt dispatch] (docs/vulkan_backend.md)
// Records and submits one dispatch, waits for it; returns its kernel time.
double Dispatcher::dispatch(const ComputePipeline& pipeline, uint32_t groups_x, uint32_t groups_y,
                            std::uint64_t pass) {
  VkDevice dev = context_.device();
  check(vkResetCommandBuffer(cmd_, 0), "resetting a command buffer");
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(cmd_, &begin), "recording commands");
  if (queries_) {
    vkCmdResetQueryPool(cmd_, queries_, 0, 2);
    vkCmdWriteTimestamp(cmd_, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, queries_, 0);
  }
  pipeline.record_dispatch(cmd_, groups_x, groups_y);
  if (queries_) vkCmdWriteTimestamp(cmd_, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries_, 1);
  // Make the shader's writes visible to the host's read of the output buffer.
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_HOST_READ_BIT};
  vkCmdPipelineBarrier(cmd_, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0,
                       nullptr, 0, nullptr);
  check(vkEndCommandBuffer(cmd_), "recording commands");

  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd_;
  check(vkResetFences(dev, 1, &fence_), "resetting a fence");
  VkResult submitted = vkQueueSubmit(context_.queue(), 1, &submit, fence_);
  VkResult waited = submitted == VK_SUCCESS ? vkWaitForFences(dev, 1, &fence_, VK_TRUE, kFenceTimeoutNs) : submitted;
  if (fault().device_lost_pass == pass) waited = VK_ERROR_DEVICE_LOST;  // PT_FAULT=device_lost:pass=N
  if (waited == VK_ERROR_DEVICE_LOST) {
    lost_ = true;
    throw Error(kExitNoDevice, "Vulkan device '" + context_.device_name() + "' was lost during pass " +
                                   std::to_string(pass) + " (VK_ERROR_DEVICE_LOST) and is not retried");
  }
  if (waited == VK_TIMEOUT) {
    throw Error(kExitNoDevice, "the Vulkan device did not finish a pass within 2 minutes; use --backend cpu");
  }
  check(waited, "running the kernel");
  if (!queries_) return 0.0;
  uint64_t stamps[2];
  check(vkGetQueryPoolResults(dev, queries_, 0, 2, sizeof stamps, stamps, sizeof(uint64_t),
                              VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
        "reading timestamps");
  return double(stamps[1] - stamps[0]) * double(context_.properties().limits.timestampPeriod) * 1e-9;
}
// [/excerpt]

}  // namespace pt::gpu
