// pt_bench's speed section on the GPU (issue 6, "Speed targets"): rays per second of the
// brute-force closest-hit search of the raycasting step (Eq. 2) on the Vulkan device, for
// the naive GLSL loop (naive_raycast.comp, the device's own reference) and for the
// renderer's intersect_scene() (intersect_raycast.comp), over the same rays, interleaved.
#pragma once

#include <span>
#include <string>

#include <glm/glm.hpp>

#include "bench/bench.h"
#include "common/scene/scene.h"

namespace pt::bench {

struct GpuRayRates {
  std::string device;
  Rate naive;     // naive_raycast.comp
  Rate renderer;  // intersect_scene() of common/kernel/intersect.glsl
  double hit_mismatch = 0.0;  // share of rays that one method hits and the other misses
};

// Casts the rays (unit directions) at the scene's triangles on the default Vulkan device,
// each kernel again and again, alternating, until each has run for `seconds`. Throws
// pt::Error(kExitNoDevice) when there is no Vulkan device.
GpuRayRates gpu_rays_per_second(const Scene& scene, std::span<const glm::vec3> origins,
                                std::span<const glm::vec3> dirs, double seconds = 1.0);

}  // namespace pt::bench
