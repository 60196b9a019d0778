// Host-mapped Vulkan buffers (see buffer.h).
#include "gpu/buffer.h"

#include <cstring>
#include <utility>

namespace pt::gpu {

Buffer::Buffer(const VulkanContext& context, VkDeviceSize size, VkBufferUsageFlags usage)
    : device_(context.device()), size_(size) {
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  check(vkCreateBuffer(device_, &info, nullptr, &buffer_), "creating a buffer");
  try {
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device_, buffer_, &req);
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = context.memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT,
                                                VK_MEMORY_PROPERTY_HOST_COHERENT_BIT | VK_MEMORY_PROPERTY_HOST_CACHED_BIT);
    VkPhysicalDeviceMemoryProperties mem;
    vkGetPhysicalDeviceMemoryProperties(context.physical_device(), &mem);
    coherent_ = mem.memoryTypes[alloc.memoryTypeIndex].propertyFlags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    check(vkAllocateMemory(device_, &alloc, nullptr, &memory_), "allocating buffer memory");
    check(vkBindBufferMemory(device_, buffer_, memory_, 0), "binding buffer memory");
    check(vkMapMemory(device_, memory_, 0, VK_WHOLE_SIZE, 0, &mapped_), "mapping buffer memory");
    if (usage & VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT) {
      VkBufferViewCreateInfo view{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
      view.buffer = buffer_;
      view.format = VK_FORMAT_R32G32B32A32_UINT;
      view.offset = 0;
      view.range = size / 16 * 16;
      check(vkCreateBufferView(device_, &view, nullptr, &view_), "creating a texel view of a buffer");
    }
  } catch (...) {
    release();
    throw;
  }
}

Buffer::~Buffer() { release(); }

Buffer::Buffer(Buffer&& o) noexcept { *this = std::move(o); }

Buffer& Buffer::operator=(Buffer&& o) noexcept {
  if (this != &o) {
    release();
    std::swap(device_, o.device_), std::swap(buffer_, o.buffer_), std::swap(memory_, o.memory_), std::swap(view_, o.view_);
    std::swap(size_, o.size_), std::swap(mapped_, o.mapped_), std::swap(coherent_, o.coherent_);
  }
  return *this;
}

void Buffer::release() {
  if (!device_) return;
  if (view_) vkDestroyBufferView(device_, view_, nullptr);
  if (mapped_) vkUnmapMemory(device_, memory_);
  if (buffer_) vkDestroyBuffer(device_, buffer_, nullptr);
  if (memory_) vkFreeMemory(device_, memory_, nullptr);
  device_ = VK_NULL_HANDLE, buffer_ = VK_NULL_HANDLE, memory_ = VK_NULL_HANDLE, mapped_ = nullptr;
  view_ = VK_NULL_HANDLE;
}

void Buffer::write(const void* src, std::size_t bytes) const {
  std::memcpy(mapped_, src, bytes);
  if (!coherent_) {
    VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE, nullptr, memory_, 0, VK_WHOLE_SIZE};
    check(vkFlushMappedMemoryRanges(device_, 1, &range), "flushing a buffer");
  }
}

void Buffer::read(void* dst, std::size_t bytes) const {
  if (!coherent_) {
    VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE, nullptr, memory_, 0, VK_WHOLE_SIZE};
    check(vkInvalidateMappedMemoryRanges(device_, 1, &range), "reading a buffer");
  }
  std::memcpy(dst, mapped_, bytes);
}

}  // namespace pt::gpu
