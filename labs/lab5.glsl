// Lab 5 (docs/labs/lab5.md): the ray/box slab test of the BVH, the acceleration structure
// that comes after the article ("yet without an acceleration structure";
// docs/acceleration.md). Write inverse_direction and box_span: the traversal
// (common/kernel/bvh.glsl) must then find the brute force's hits bit for bit. Built instead
// of common/kernel/box_slab.glsl when you configure with -DPT_LAB=5. Graded by `ctest -L lab5`.
// Written in the GLSL/C++ subset (docs/README.md): it runs on both backends.

#include "labs/lab_support.glsl"
#include "common/kernel/intersect.glsl"

// dir: the ray's unit direction; any component may be exactly 0 (a ray along an axis) or
// -0. Return 1 / dir component by component, for box_span: with no value that can make
// box_span multiply 0 by an infinity (0 * inf is NaN).
vec3 inverse_direction(vec3 dir) {
  // Your code here. Remove the line below when you are done.
  return vec3(PT_LAB_NOT_WRITTEN(5, inverse_direction)) * dir;
}

// ray: the ray (origin, unit dir); inv_dir: inverse_direction(ray.dir); lo, hi: the box's
// corners (lo <= hi; a box may be flat: lo == hi on an axis); t_max: the nearest hit so far.
// Return vec2(enter, exit): the distances along the ray within the box, clipped to
// [0, t_max]. The traversal skips the box when NOT (enter <= exit), so a NaN means "miss"
// too. Never answer "miss" for a box holding a triangle that hit_triangle() hits at a
// distance up to t_max (t_max itself included), whatever the rounding of either test: a
// skipped box loses a hit, and the hits must equal the brute force's bit for bit. Saying
// "hit" for a box the ray misses only costs time.
vec2 box_span(Ray ray, vec3 inv_dir, vec3 lo, vec3 hi, float t_max) {
  // Your code here. Remove the lines below when you are done.
  float nan = PT_LAB_NOT_WRITTEN(5, box_span) * t_max;
  return vec2(nan * (lo.x - ray.origin.x), nan * (hi.x - ray.origin.x) * inv_dir.x);
}
