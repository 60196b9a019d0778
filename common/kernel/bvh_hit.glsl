// The two tests a walk through the bounding volume hierarchy is made of, shared by the
// plain walk every reader meets (common/kernel/bvh.glsl, also the CPU's fallback) and the
// GPU's tuned form of it (gpu/bvh_walk.glsl): the ray against a node's box, and against a
// triangle with the brute force's tie rule. The step after the article's GPU section.
#ifndef PT_BVH_HIT_GLSL
#define PT_BVH_HIT_GLSL

#include "common/kernel/intersect.glsl"

// The slab test, declared here and defined by the build (kernel_definitions.glsl,
// cmake/Labs.cmake): common/kernel/box_slab.glsl, or labs/lab5.glsl in lab 5's build.
// inverse_direction(dir): 1 / dir for box_span, without a NaN from a zero component.
// box_span(): the distances [enter, exit] along the ray within the box lo..hi, clipped to
// [0, t_max]; enter > exit: the ray misses it. Never a miss for a box that holds a triangle
// hit_triangle() hits within t_max.
vec3 inverse_direction(vec3 dir);
vec2 box_span(Ray ray, vec3 inv_dir, vec3 lo, vec3 hi, float t_max);

// Whether the ray passes through the box lo..hi within [0, t_max] (never a false "no").
// t_max itself counts: a triangle at exactly the best distance may still win on index.
bool hit_box(Ray ray, vec3 inv_dir, vec3 lo, vec3 hi, float t_max) {
  vec2 span = box_span(ray, inv_dir, lo, hi, t_max);
  return span.x <= span.y;
}

// hit_triangle(), with the brute force's tie rule kept in any order: of two hits at the
// same distance the lower index wins. hit_triangle() keeps `best` on an equal t, which in
// index order is the lower index; the BVH may test the lower index later, so it is given
// the next float above best.t as its bound (t < next(best.t) is t <= best.t). One call of
// hit_triangle() for both cases: as two calls, neighbouring rays that took different
// branches ran both tests on lavapipe (docs/acceleration.md, "Measured").
Hit hit_triangle_tie(Ray ray, RayShear rs, uint index, Hit best) {
  Hit bound = best;
  if (best.kind == kPrimTriangle && index < best.prim) {
    bound.t = intBitsToFloat(floatBitsToInt(best.t) + 1);  // best.t > 0 and finite here
  }
  Hit found = hit_triangle(ray, rs, index, bound);
  return found.prim == index && found.kind == kPrimTriangle ? found : best;
}

#endif  // PT_BVH_HIT_GLSL
