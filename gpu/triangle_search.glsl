// The GPU's searches over the triangles and the spheres (common/kernel/intersect.glsl declares
// them). The triangles: through the BVH when the pass asks for it (gpu/bvh_walk.glsl, the walk
// of common/kernel/bvh.glsl tuned for lavapipe), else the triangles in index order, one
// hit_triangle() at a time, as the article's brute force. The same hits.
#ifndef PT_GPU_TRIANGLE_SEARCH_GLSL
#define PT_GPU_TRIANGLE_SEARCH_GLSL

#include "gpu/bvh_walk.glsl"

Hit nearest_triangle(Ray ray, RayShear rs, Hit best) {
  if (params.accel == kAccelBvh) return nearest_triangle_bvh(ray, rs, best);
  return nearest_triangle_in_order(ray, rs, best);
}

// Whether any triangle is hit closer than t_max: the BVH's any-hit walk, or the loop.
bool occluded_triangles(Ray ray, RayShear rs, float t_max) {
  if (params.accel == kAccelBvh) return occluded_bvh(ray, rs, t_max);
  return nearest_triangle_in_order(ray, rs, Hit(t_max, 0.0f, 0.0f, 0u, kPrimNone)).kind != kPrimNone;
}

// The GPU's search over the spheres (intersect.glsl declares it): the loop in index order.
Hit nearest_sphere(Ray ray, Hit best) {
  return nearest_sphere_in_order(ray, best);
}

#endif  // PT_GPU_TRIANGLE_SEARCH_GLSL
