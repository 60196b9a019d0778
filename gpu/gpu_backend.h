// The Vulkan compute backend: runs a stage's kernel (its integrator compiled to SPIR-V)
// on any Vulkan device, a real GPU or Mesa's lavapipe. The article: "per-pixel work is
// independent, so the GPU runs one thread per pixel".
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "common/render/backend.h"

namespace pt::gpu {

// device: "" for the best device, an index, or part of a device name. Throws
// pt::Error(kExitNoDevice) when there is no Vulkan, no device, or it cannot run the kernel.
std::unique_ptr<Backend> create_backend(const StageKernels& kernels, const std::string& device);

// The same on the device of `session`, whose compiled kernels it reuses and adds to: what a
// program that makes many backends in turn uses (the test programs: tests/support/test_render.cpp).
class DeviceSession;
std::unique_ptr<Backend> create_backend(const StageKernels& kernels, std::shared_ptr<DeviceSession> session);

// The Vulkan devices and their kinds, without making a device or a pipeline (what
// --backend auto weighs: common/app/app.h, Backends::gpu_devices). Throws
// pt::Error(kExitNoDevice) when there is no Vulkan, no driver or no device.
std::vector<VulkanDevice> vulkan_devices();

}  // namespace pt::gpu
