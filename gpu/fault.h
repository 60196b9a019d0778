// Fault injection for the reliability tests (docs/reliability.md): the environment variable
// PT_FAULT makes the Vulkan backend behave as a broken machine would, so that each failure
// the renderer must survive can be tested on any machine, lavapipe included:
//   PT_FAULT=no_loader           libvulkan.so.1 cannot be opened
//   PT_FAULT=no_device           the loader lists no device
//   PT_FAULT=small_limits        the device allows 64 KiB storage buffers and a 1 MiB heap
//   PT_FAULT=small_texel_limit   the device reads at most 65,536 texels from a texel buffer
//                                (the Vulkan minimum; the BVH's nodes are read as texels)
//   PT_FAULT=device_lost:pass=N  the Nth pass on the device (from 1) ends in VK_ERROR_DEVICE_LOST
// Not part of the article: the machinery of the GPU backend.
#pragma once

#include <cstdint>

namespace pt::gpu {

struct Fault {
  bool no_loader = false;
  bool no_device = false;
  bool small_limits = false;
  bool small_texel_limit = false;
  std::uint64_t device_lost_pass = 0;  // 0: never
};

// PT_FAULT parsed once; an unknown value throws pt::Error(kExitBadOption) naming the choices.
const Fault& fault();

// The limits small_limits pretends.
constexpr std::uint64_t kFaultStorageBufferRange = 64 * 1024;
constexpr std::uint64_t kFaultHeapSize = 1024 * 1024;
constexpr std::uint32_t kFaultTexelBufferElements = 65536;  // small_texel_limit

}  // namespace pt::gpu
