// Instance, device choice, logical device and queue (see vulkan_context.h).
#include "gpu/vulkan_context.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>

#include <atomic>
#include <cstdio>
#include <cstring>

#include "common/base/error.h"
#include "gpu/fault.h"

namespace pt::gpu {

namespace {

const char* result_name(VkResult r) {
  switch (r) {
    case VK_ERROR_OUT_OF_HOST_MEMORY: return "out of host memory";
    case VK_ERROR_OUT_OF_DEVICE_MEMORY: return "out of device memory";
    case VK_ERROR_INITIALIZATION_FAILED: return "initialization failed";
    case VK_ERROR_DEVICE_LOST: return "device lost";
    case VK_ERROR_INCOMPATIBLE_DRIVER: return "incompatible driver";
    case VK_ERROR_FEATURE_NOT_PRESENT: return "feature not present";
    case VK_ERROR_EXTENSION_NOT_PRESENT: return "extension not present";
    case VK_ERROR_LAYER_NOT_PRESENT: return "layer not present";
    default: return "error";
  }
}

// Lower rank = preferred: a real GPU first, lavapipe (a CPU device) last.
int type_rank(VkPhysicalDeviceType t) {
  switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
    default: return 4;
  }
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

std::atomic<int> g_validation_errors{0};

// PT_VULKAN_VALIDATION=1: the Khronos validation layer checks every call; its errors are
// printed and counted (validation_errors()), its warnings printed.
bool validation_requested() {
  const char* v = std::getenv("PT_VULKAN_VALIDATION");
  return v && *v && std::strcmp(v, "0") != 0;
}

VKAPI_ATTR VkBool32 VKAPI_CALL on_validation_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                     VkDebugUtilsMessageTypeFlagsEXT,
                                                     const VkDebugUtilsMessengerCallbackDataEXT* data, void*) {
  bool error = severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  if (error) g_validation_errors++;
  std::fprintf(stderr, "vulkan validation %s: %s\n", error ? "error" : "warning", data->pMessage);
  return VK_FALSE;
}

const char* kNoVulkanHint =
    "install a Vulkan driver (on Debian: apt-get install mesa-vulkan-drivers) or use --backend cpu";

}  // namespace

void check(VkResult result, const char* what) {
  if (result == VK_SUCCESS) return;
  throw Error(kExitNoDevice, std::string("Vulkan: ") + what + " failed (" + result_name(result) + ", " +
                                 std::to_string(int(result)) + "); use --backend cpu");
}

VulkanContext::VulkanContext(const std::string& device_request) {
  try {
    create(device_request);
  } catch (...) {
    release();
    throw;
  }
}

namespace {

// The renderer as every instance it makes names it: Vulkan 1.1.
VkApplicationInfo application_info() {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "staged path tracer";
  app.apiVersion = VK_API_VERSION_1_1;
  return app;
}

// Opens libvulkan.so.1 (volk), or throws.
void open_loader() {
  if (fault().no_loader || volkInitialize() != VK_SUCCESS) {
    throw Error(kExitNoDevice, std::string("no Vulkan loader (libvulkan.so.1) on this machine; ") + kNoVulkanHint);
  }
}

void throw_no_device() { throw Error(kExitNoDevice, std::string("no Vulkan device found; ") + kNoVulkanHint); }

}  // namespace

std::vector<DeviceInfo> list_devices() {
  open_loader();
  VkApplicationInfo app = application_info();
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  VkInstance instance = VK_NULL_HANDLE;
  VkResult r = vkCreateInstance(&info, nullptr, &instance);
  if (r == VK_ERROR_INCOMPATIBLE_DRIVER) throw Error(kExitNoDevice, std::string("no Vulkan driver; ") + kNoVulkanHint);
  check(r, "creating an instance");
  volkLoadInstanceOnly(instance);  // VulkanContext loads its own instance's functions again
  uint32_t count = 0;
  r = vkEnumeratePhysicalDevices(instance, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  if (r == VK_SUCCESS) r = vkEnumeratePhysicalDevices(instance, &count, devices.data());
  std::vector<DeviceInfo> list;
  if (r >= 0) {  // VK_INCOMPLETE: a device appeared in between; the ones read are listed
    for (uint32_t i = 0; i < count && i < devices.size(); i++) {
      VkPhysicalDeviceProperties p;
      vkGetPhysicalDeviceProperties(devices[i], &p);
      list.push_back(DeviceInfo{i, p.deviceName, p.deviceType});
    }
  }
  vkDestroyInstance(instance, nullptr);
  if (r < 0) check(r, "listing devices");
  if (fault().no_device) list.clear();
  if (list.empty()) throw_no_device();
  return list;
}

void VulkanContext::create(const std::string& device_request) {
  open_loader();
  // [excerpt instance] (docs/vulkan_backend.md)
  VkApplicationInfo app = application_info();
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  const char* layer = "VK_LAYER_KHRONOS_validation";
  const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
  VkDebugUtilsMessengerCreateInfoEXT messenger{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  messenger.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messenger.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                          VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  messenger.pfnUserCallback = on_validation_message;
  const bool validate = validation_requested();
  if (validate) {
    uint32_t n = 0;
    vkEnumerateInstanceLayerProperties(&n, nullptr);
    std::vector<VkLayerProperties> layers(n);
    vkEnumerateInstanceLayerProperties(&n, layers.data());
    bool found = false;
    for (const VkLayerProperties& l : layers) found = found || std::strcmp(l.layerName, layer) == 0;
    if (!found) {
      throw Error(kExitNoDevice, "PT_VULKAN_VALIDATION is set but the layer VK_LAYER_KHRONOS_validation is not "
                                 "installed; apt-get install vulkan-validationlayers, or unset PT_VULKAN_VALIDATION");
    }
    info.enabledLayerCount = 1;
    info.ppEnabledLayerNames = &layer;
    info.enabledExtensionCount = 1;
    info.ppEnabledExtensionNames = &extension;
    info.pNext = &messenger;  // also checks vkCreateInstance and vkDestroyInstance
  }
  VkResult r = vkCreateInstance(&info, nullptr, &instance_);
  if (r == VK_ERROR_INCOMPATIBLE_DRIVER) throw Error(kExitNoDevice, std::string("no Vulkan driver; ") + kNoVulkanHint);
  check(r, "creating an instance");
  volkLoadInstance(instance_);
  if (validate) check(vkCreateDebugUtilsMessengerEXT(instance_, &messenger, nullptr, &messenger_), "creating the validation messenger");
  // [/excerpt]

  uint32_t count = 0;
  check(vkEnumeratePhysicalDevices(instance_, &count, nullptr), "listing devices");
  std::vector<VkPhysicalDevice> devices(count);
  check(vkEnumeratePhysicalDevices(instance_, &count, devices.data()), "listing devices");
  if (fault().no_device) count = 0;
  if (count == 0) throw_no_device();

  // [excerpt choose_device] (docs/vulkan_backend.md)
  // Choose: the request (index or name) if any, else the best type.
  std::string request = device_request;
  if (request.empty() && std::getenv("PT_VULKAN_DEVICE")) request = std::getenv("PT_VULKAN_DEVICE");
  std::string listing;
  int best = -1;
  for (uint32_t i = 0; i < count; i++) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(devices[i], &p);
    listing += (listing.empty() ? "" : ", ") + std::to_string(i) + " '" + p.deviceName + "'";
    bool match = request.empty() ? (best < 0 || type_rank(p.deviceType) < type_rank(properties_.deviceType))
                                 : (request == std::to_string(i) || lower(p.deviceName).find(lower(request)) != std::string::npos);
    if (match && (request.empty() || best < 0)) best = int(i), properties_ = p;
  }
  if (best < 0) {
    throw Error(kExitNoDevice, "no Vulkan device matches '" + request + "'; the devices are " + listing);
  }
  physical_ = devices[best];
  // [/excerpt]
  // The largest heap that host-visible memory (which the buffers use) comes from.
  VkPhysicalDeviceMemoryProperties mem;
  vkGetPhysicalDeviceMemoryProperties(physical_, &mem);
  for (uint32_t i = 0; i < mem.memoryTypeCount; i++) {
    if (mem.memoryTypes[i].propertyFlags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) {
      heap_size_ = std::max(heap_size_, mem.memoryHeaps[mem.memoryTypes[i].heapIndex].size);
    }
  }
  if (fault().small_limits) {
    properties_.limits.maxStorageBufferRange = uint32_t(kFaultStorageBufferRange);
    heap_size_ = kFaultHeapSize;
  }
  if (fault().small_texel_limit) properties_.limits.maxTexelBufferElements = kFaultTexelBufferElements;

  // [excerpt device_queue] (docs/vulkan_backend.md)
  // One queue family that can compute.
  uint32_t families = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical_, &families, nullptr);
  std::vector<VkQueueFamilyProperties> family(families);
  vkGetPhysicalDeviceQueueFamilyProperties(physical_, &families, family.data());
  queue_family_ = families;
  for (uint32_t i = 0; i < families && queue_family_ == families; i++) {
    if (family[i].queueFlags & VK_QUEUE_COMPUTE_BIT) queue_family_ = i;
  }
  if (queue_family_ == families) {
    throw Error(kExitNoDevice, std::string("Vulkan device '") + properties_.deviceName + "' cannot run compute shaders; use --backend cpu");
  }
  timestamp_bits_ = family[queue_family_].timestampValidBits;

  float priority = 1.0f;
  VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queue_info.queueFamilyIndex = queue_family_;
  queue_info.queueCount = 1;
  queue_info.pQueuePriorities = &priority;
  VkDeviceCreateInfo device_info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  device_info.queueCreateInfoCount = 1;
  device_info.pQueueCreateInfos = &queue_info;
  check(vkCreateDevice(physical_, &device_info, nullptr, &device_), "creating the device");
  volkLoadDevice(device_);
  vkGetDeviceQueue(device_, queue_family_, 0, &queue_);
  // [/excerpt]

  VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pool_info.queueFamilyIndex = queue_family_;
  check(vkCreateCommandPool(device_, &pool_info, nullptr, &pool_), "creating a command pool");
}

VulkanContext::~VulkanContext() { release(); }

void VulkanContext::release() {
  if (device_) {
    vkDeviceWaitIdle(device_);
    if (pool_) vkDestroyCommandPool(device_, pool_, nullptr);
    vkDestroyDevice(device_, nullptr);
  }
  if (messenger_) vkDestroyDebugUtilsMessengerEXT(instance_, messenger_, nullptr);
  if (instance_) vkDestroyInstance(instance_, nullptr);
  device_ = VK_NULL_HANDLE, pool_ = VK_NULL_HANDLE, instance_ = VK_NULL_HANDLE, messenger_ = VK_NULL_HANDLE;
}

int validation_errors() { return g_validation_errors.load(); }

uint32_t VulkanContext::memory_type(uint32_t type_bits, VkMemoryPropertyFlags required,
                                    VkMemoryPropertyFlags preferred) const {
  VkPhysicalDeviceMemoryProperties mem;
  vkGetPhysicalDeviceMemoryProperties(physical_, &mem);
  uint32_t fallback = UINT32_MAX;
  for (uint32_t i = 0; i < mem.memoryTypeCount; i++) {
    VkMemoryPropertyFlags f = mem.memoryTypes[i].propertyFlags;
    if (!(type_bits & (1u << i)) || (f & required) != required) continue;
    if ((f & preferred) == preferred) return i;
    if (fallback == UINT32_MAX) fallback = i;
  }
  if (fallback == UINT32_MAX) {
    throw Error(kExitNoDevice, std::string("Vulkan device '") + properties_.deviceName +
                                   "' has no host-visible memory for storage buffers; use --backend cpu");
  }
  return fallback;
}

}  // namespace pt::gpu
