// The scene's spheres as a structure of arrays (sphere_soa.h): the CPU kernels' layout for
// the block test of the spheres (Eq. 2's raycasting).
#include "cpu/sphere_soa.h"

#include "cpu/kernel_prelude.h"

namespace pt {

namespace sphere_kernel {  // the kernel's sphere_power_terms(), compiled as the kernels compile it
using namespace pt::glsl;
#include "common/kernel/sphere_power.glsl"
}  // namespace sphere_kernel

SphereSoa::SphereSoa(std::span<const Sphere> spheres, uint block) {
  count = uint(spheres.size());
  stride = uint((spheres.size() + block - 1) / block * block);
  data.assign(std::size_t(stride) * kArrayCount, 0.0f);
  for (std::size_t i = 0; i < spheres.size(); i++) {
    const glm::vec3 c = spheres[i].center;
    // The terms hit_sphere() computes from the sphere alone, by the kernel's own function.
    const sphere_kernel::SpherePowerTerms t = sphere_kernel::sphere_power_terms(c, spheres[i].radius);
    const float values[kArrayCount] = {c.x,     c.y,          c.z,          spheres[i].radius, t.center_power,
                                       t.lead_abs, t.others, t.abs_center.x, t.abs_center.y, t.abs_center.z};
    for (int k = 0; k < kArrayCount; k++) data[std::size_t(k) * stride + i] = values[k];
  }
}

}  // namespace pt
