// A Vulkan buffer with its own memory, mapped for the host to write and read: the scene
// arrays, the per-pass parameters and the pass output all live in these. Host-visible
// memory works on every device (and is all lavapipe has); device-local is preferred.
#pragma once

#include <cstddef>

#include "gpu/vulkan_context.h"

namespace pt::gpu {

class Buffer {
 public:
  Buffer() = default;
  Buffer(const VulkanContext& context, VkDeviceSize size, VkBufferUsageFlags usage);
  ~Buffer();
  Buffer(Buffer&& other) noexcept;
  Buffer& operator=(Buffer&& other) noexcept;

  VkBuffer handle() const { return buffer_; }
  // The buffer seen as uvec4 texels (VK_FORMAT_R32G32B32A32_UINT), made when `usage` has
  // VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT, else VK_NULL_HANDLE.
  VkBufferView texel_view() const { return view_; }
  VkDeviceSize size() const { return size_; }
  void* data() const { return mapped_; }
  // Copies bytes in (before a dispatch) or out (after it), flushing/invalidating as needed.
  void write(const void* src, std::size_t bytes) const;
  void read(void* dst, std::size_t bytes) const;

 private:
  void release();

  VkDevice device_ = VK_NULL_HANDLE;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkBufferView view_ = VK_NULL_HANDLE;
  VkDeviceSize size_ = 0;
  void* mapped_ = nullptr;
  bool coherent_ = true;
};

}  // namespace pt::gpu
