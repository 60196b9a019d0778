// The GPU's search over the triangles (common/kernel/intersect.glsl declares it): through
// the BVH (common/kernel/bvh.glsl) when the pass asks for it, else the triangles in index
// order, one hit_triangle() at a time, as the article's brute force. The same hits.
#ifndef PT_GPU_TRIANGLE_SEARCH_GLSL
#define PT_GPU_TRIANGLE_SEARCH_GLSL

#include "common/kernel/bvh.glsl"

Hit nearest_triangle(Ray ray, RayShear rs, Hit best) {
  if (params.accel == kAccelBvh) return nearest_triangle_bvh(ray, rs, best);
  return nearest_triangle_in_order(ray, rs, best);
}

#endif  // PT_GPU_TRIANGLE_SEARCH_GLSL
