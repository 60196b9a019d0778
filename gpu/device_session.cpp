// The device and its compiled kernels, shared by backends (see device_session.h).
#include "gpu/device_session.h"

namespace pt::gpu {

std::shared_ptr<const KernelProgram> DeviceSession::program(std::span<const uint32_t> spirv, uint32_t features,
                                                            uint32_t uniform_triangles) {
  std::lock_guard<std::mutex> lock(mutex_);
  std::shared_ptr<const KernelProgram>& p = programs_[Key{spirv.data(), spirv.size(), features, uniform_triangles}];
  if (!p) p = std::make_shared<const KernelProgram>(context_, spirv, features, uniform_triangles);
  return p;
}

std::size_t DeviceSession::compiled() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return programs_.size();
}

}  // namespace pt::gpu
