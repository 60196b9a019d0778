// pt_bench's GPU ray casting harness: one compute kernel over a buffer of rays on a Vulkan
// device, a single dispatch of 64-ray workgroups recorded once and submitted again and
// again, timed by the wall clock and by the process's CPU time (lavapipe's threads too).
// Used by the speed section (speed_gpu.cpp: the brute-force search of Eq. 2's raycasting)
// and the acceleration section (accel_gpu.cpp: the GPU's BVH walk, gpu/bvh_walk.glsl).
#pragma once

#include <chrono>
#include <cstdint>
#include <ctime>
#include <span>

#include "gpu/buffer.h"
#include "gpu/compute_pipeline.h"
#include "gpu/vulkan_context.h"

namespace pt::bench {

constexpr uint32_t kRaysPerGroup = 64;  // the ray kernels' local_size_x

// One kernel's pipeline and its recorded dispatch over every ray.
class RayKernel {
 public:
  RayKernel(const gpu::VulkanContext& context, std::span<const uint32_t> spirv, uint features,
            const gpu::Buffer* const (&buffers)[gpu::kBindingCount], uint32_t groups, uint32_t uniform_triangles = 0)
      : context_(context), pipeline_(context, spirv, features, uniform_triangles) {
    VkDevice dev = context.device();
    pipeline_.bind_buffers(buffers);
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = context.command_pool();
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    gpu::check(vkAllocateCommandBuffers(dev, &alloc, &cmd_), "allocating a command buffer");
    VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    gpu::check(vkCreateFence(dev, &fence_info, nullptr, &fence_), "creating a fence");
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    gpu::check(vkBeginCommandBuffer(cmd_, &begin), "recording commands");
    pipeline_.record_dispatch(cmd_, groups, 1);
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT,
                            VK_ACCESS_HOST_READ_BIT};
    vkCmdPipelineBarrier(cmd_, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0,
                         nullptr, 0, nullptr);
    gpu::check(vkEndCommandBuffer(cmd_), "recording commands");
  }
  ~RayKernel() {
    vkDeviceWaitIdle(context_.device());
    vkDestroyFence(context_.device(), fence_, nullptr);
    vkFreeCommandBuffers(context_.device(), context_.command_pool(), 1, &cmd_);
  }
  RayKernel(const RayKernel&) = delete;
  RayKernel& operator=(const RayKernel&) = delete;

  // Submits the dispatch and waits for it; adds its wall and process CPU seconds. The
  // first run is a warm-up (the driver may finish compiling then) and is not counted.
  void run() {
    VkDevice dev = context_.device();
    std::clock_t cpu0 = std::clock();
    auto t0 = std::chrono::steady_clock::now();
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd_;
    gpu::check(vkResetFences(dev, 1, &fence_), "resetting a fence");
    gpu::check(vkQueueSubmit(context_.queue(), 1, &submit, fence_), "running a kernel");
    gpu::check(vkWaitForFences(dev, 1, &fence_, VK_TRUE, UINT64_MAX), "running a kernel");
    if (!warm_) {
      warm_ = true;
      return;
    }
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    cpu += double(std::clock() - cpu0) / CLOCKS_PER_SEC;
    runs++;
  }

  double wall = 0.0, cpu = 0.0;  // seconds of the counted runs
  std::uint64_t runs = 0;

 private:
  const gpu::VulkanContext& context_;
  gpu::ComputePipeline pipeline_;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  bool warm_ = false;
};

}  // namespace pt::bench
