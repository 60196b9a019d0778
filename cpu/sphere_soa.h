// The scene's spheres as a structure of arrays, for the CPU kernels' block test of the
// spheres (cpu/sphere_lanes.h; the raycasting step of the article, Eq. 2, for its spheres).
// Per sphere the numbers hit_sphere() of common/kernel/intersect.glsl reads or computes from
// the sphere alone: the centre, the radius, and the terms of
// sphere_power_from_world_origin() that do not depend on the ray, computed by the kernel's
// own sphere_power_terms() (common/kernel/sphere_power.glsl), so that the lanes round as the
// scalar test does. Each array is padded to a multiple of the block size; the lanes mask
// the padding by index.
#pragma once

#include <span>
#include <vector>

#include "common/kernel/scene_types.h"

namespace pt {

struct SphereSoa {
  // The arrays, each `stride` floats, in this order.
  enum Array { kCx, kCy, kCz, kRadius, kPowerTerm, kLeadAbs, kOthers, kAx, kAy, kAz, kArrayCount };
  std::vector<float> data;
  uint stride = 0;  // the padded sphere count
  uint count = 0;   // the spheres

  explicit SphereSoa(std::span<const Sphere> spheres, uint block = 8);
  const float* array(Array a) const { return data.data() + std::size_t(a) * stride; }
};

}  // namespace pt
