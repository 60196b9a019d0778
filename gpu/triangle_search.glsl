// The GPU's search over all triangles (common/kernel/intersect.glsl declares it): the
// triangles in index order, one hit_triangle() at a time, as the article's brute force.
#ifndef PT_GPU_TRIANGLE_SEARCH_GLSL
#define PT_GPU_TRIANGLE_SEARCH_GLSL

Hit nearest_triangle(Ray ray, RayShear rs, Hit best) {
  return nearest_triangle_in_order(ray, rs, best);
}

#endif  // PT_GPU_TRIANGLE_SEARCH_GLSL
