// The Vulkan objects every compute job needs, behind one RAII type: the loader (opened at
// run time through volk, so a machine without Vulkan still runs the CPU backend), an
// instance without a window, the chosen physical device, a logical device with one compute
// queue, and a command pool. Not part of the article: the machinery of the GPU backend.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <volk.h>

namespace pt::gpu {

// Throws pt::Error(kExitNoDevice) naming `what` if result is not VK_SUCCESS.
void check(VkResult result, const char* what);

struct DeviceInfo {
  uint32_t index;  // what --device N names
  std::string name;
  VkPhysicalDeviceType type;
};

// The Vulkan devices in the loader's order, found cheaply: a bare instance is made and
// destroyed, no device and no pipeline (what --backend auto weighs; VulkanContext makes the
// device). Throws pt::Error(kExitNoDevice) when there is no loader, no driver or no device
// (PT_FAULT=no_loader and no_device too), with the same words as VulkanContext.
std::vector<DeviceInfo> list_devices();

class VulkanContext {
 public:
  // device: "" (best device: discrete, integrated, virtual, then CPU such as lavapipe),
  // a device index, or part of a device name (case-insensitive).
  explicit VulkanContext(const std::string& device);
  ~VulkanContext();
  VulkanContext(const VulkanContext&) = delete;
  VulkanContext& operator=(const VulkanContext&) = delete;

  VkDevice device() const { return device_; }
  VkPhysicalDevice physical_device() const { return physical_; }
  VkQueue queue() const { return queue_; }
  VkCommandPool command_pool() const { return pool_; }
  const VkPhysicalDeviceProperties& properties() const { return properties_; }
  std::string device_name() const { return properties_.deviceName; }
  bool has_timestamps() const { return timestamp_bits_ > 0; }
  // The largest heap of host-visible memory, in bytes (what every buffer is made of).
  VkDeviceSize heap_size() const { return heap_size_; }

  // A memory type index with all of `required` among `type_bits`, preferring `preferred`.
  uint32_t memory_type(uint32_t type_bits, VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred) const;

 private:
  void create(const std::string& device);
  void release();

  VkInstance instance_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties properties_{};
  uint32_t queue_family_ = 0;
  uint32_t timestamp_bits_ = 0;
  VkDeviceSize heap_size_ = 0;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;  // PT_VULKAN_VALIDATION only
};

// Errors the validation layer reported so far in this process (PT_VULKAN_VALIDATION=1).
int validation_errors();

}  // namespace pt::gpu
