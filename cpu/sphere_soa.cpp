// The scene's spheres as a structure of arrays (sphere_soa.h): the CPU kernels' layout for
// the block test of the spheres (Eq. 2's raycasting).
#include "cpu/sphere_soa.h"

#include <cmath>

namespace pt {

SphereSoa::SphereSoa(std::span<const Sphere> spheres, uint block) {
  count = uint(spheres.size());
  stride = uint((spheres.size() + block - 1) / block * block);
  data.assign(std::size_t(stride) * kArrayCount, 0.0f);
  for (std::size_t i = 0; i < spheres.size(); i++) {
    const glm::vec3 c = spheres[i].center;
    const float radius = spheres[i].radius;
    // sphere_power_from_world_origin()'s terms of the sphere alone, operation by operation
    // (the build does not contract a * b + c into one rounding: -ffp-contract=off).
    const glm::vec3 a(std::fabs(c.x), std::fabs(c.y), std::fabs(c.z));
    float m = a.z;
    float others = a.x * a.x + a.y * a.y;
    if (a.x >= a.y && a.x >= a.z) {
      m = a.x;
      others = a.y * a.y + a.z * a.z;
    } else if (a.y >= a.z) {
      m = a.y;
      others = a.x * a.x + a.z * a.z;
    }
    const float lead = (m - radius) * (m + radius);
    const float values[kArrayCount] = {c.x, c.y, c.z, radius, lead + others, std::fabs(lead), others, a.x, a.y, a.z};
    for (int k = 0; k < kArrayCount; k++) data[std::size_t(k) * stride + i] = values[k];
  }
}

}  // namespace pt
