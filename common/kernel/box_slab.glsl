// The ray/box slab test of the BVH traversal (common/kernel/bvh_hit.glsl, which declares these
// two functions): the step after the article's GPU section, which ends "yet without an
// acceleration structure". Lab 5 (docs/labs/lab5.md) asks the student for them: its build
// compiles labs/lab5.glsl instead of this file.
#ifndef PT_BOX_SLAB_GLSL
#define PT_BOX_SLAB_GLSL

#include "common/kernel/box_pad.glsl"
#include "common/kernel/intersect.glsl"

// 1 / dir, with the infinities of a zero component made the largest float: then a box
// corner at distance 0 along that axis gives 0, not 0 * inf = NaN, and the ray inside the
// slab stays inside it.
vec3 inverse_direction(vec3 dir) {
  return clamp(vec3(1.0f / dir.x, 1.0f / dir.y, 1.0f / dir.z), vec3(-kInfinity), vec3(kInfinity));
}

// The distances [enter, exit] along the ray within the box lo..hi, clipped to [0, t_max]
// and erring on the large side; enter > exit: the ray misses it. The corners are taken
// relative to the origin as hit_triangle() takes the vertices: rounding is monotone, so
// the rounded vertices stay inside the rounded corners. A NaN (a NaN ray) fails every
// comparison below and leaves the interval as it was: such a ray is never cut off early.
vec2 box_span(Ray ray, vec3 inv_dir, vec3 lo, vec3 hi, float t_max) {
  vec3 a_lo = lo - ray.origin;
  vec3 a_hi = hi - ray.origin;
  float pad = kBoxPad * (larger(abs(a_lo.x), abs(a_hi.x)) + larger(abs(a_lo.y), abs(a_hi.y)) +
                         larger(abs(a_lo.z), abs(a_hi.z)));
  vec3 t0 = (a_lo - vec3(pad)) * inv_dir;
  vec3 t1 = (a_hi + vec3(pad)) * inv_dir;
  float t_enter = 0.0f;
  float t_exit = t_max;
  float near_x = t0.x < t1.x ? t0.x : t1.x;
  float far_x = (t0.x < t1.x ? t1.x : t0.x) * kBoxRoundUp;
  float near_y = t0.y < t1.y ? t0.y : t1.y;
  float far_y = (t0.y < t1.y ? t1.y : t0.y) * kBoxRoundUp;
  float near_z = t0.z < t1.z ? t0.z : t1.z;
  float far_z = (t0.z < t1.z ? t1.z : t0.z) * kBoxRoundUp;
  t_enter = near_x > t_enter ? near_x : t_enter;
  t_enter = near_y > t_enter ? near_y : t_enter;
  t_enter = near_z > t_enter ? near_z : t_enter;
  t_exit = far_x < t_exit ? far_x : t_exit;
  t_exit = far_y < t_exit ? far_y : t_exit;
  t_exit = far_z < t_exit ? far_z : t_exit;
  return vec2(t_enter, t_exit);
}

#endif  // PT_BOX_SLAB_GLSL
