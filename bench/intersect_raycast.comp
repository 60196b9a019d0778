// The speed section's GPU row for the renderer's own intersection (issue 6): intersect_scene()
// of common/kernel/intersect.glsl, exactly as the stage kernels include it, on one camera
// ray per invocation read from a buffer, the hit written out; no camera, sampling or film.
// Comparable with the CPU row "intersect_scene (renderer)" and with the naive loop
// (naive_raycast.comp). Article: the raycasting step (Eq. 2), its closest-hit search. The
// rays sit in binding 3 (gpu/kernel_bindings.glsl's point_lights: a position and an intensity 16 bytes
// apart in a 48-byte entry, read here as origin and direction, and cos_outer after the intensity as
// the bound of the search: kInfinity, or a shadow ray's t_max in the accel section; cos_inner,
// the entry's last float, 1 for the any-hit search occluded_scene() instead); params.triangle_count is the triangle count,
// params.width the ray count. With params.accel = kAccelBvh and the BVH at bindings 9 and 10
// it walks common/kernel/bvh.glsl instead (the accel section, accel_gpu.cpp). The build's
// kernel_definitions.glsl defines what the kernel files declare (cmake/Labs.cmake).
#version 460
#extension GL_GOOGLE_include_directive : require
#include "common/kernel/scene_types.h"
#include "gpu/kernel_bindings.glsl"
#include "common/kernel/camera.glsl"
#include "common/kernel/intersect.glsl"
#include "kernel_definitions.glsl"
#include "gpu/triangle_search.glsl"

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= params.width) return;
  Ray ray = Ray(point_lights[i].position, point_lights[i].intensity);
  float bound = point_lights[i].cos_outer;  // the ray's bound (a shadow ray's t_max) or kInfinity
  if (point_lights[i].cos_inner > 0.5f) {  // the any-hit search: the bound where blocked
    pass_output[i] = vec4(occluded_scene(ray, bound) ? bound : kInfinity, 0.0f, 0.0f, 0.0f);
    return;
  }
  Hit hit = intersect_scene(ray, bound);
  pass_output[i] = vec4(hit.kind == kPrimNone ? kInfinity : hit.t, hit.b1, hit.b2, float(hit.prim));
}
