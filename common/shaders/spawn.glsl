// Starting a new ray from a surface without hitting that surface again ("acne") and
// without slipping through a neighbouring one ("light leaks"), at any scene scale: the
// origin moves off the surface by a few units in the last place of its own coordinates
// (Wächter and Binder, "A Fast and Robust Method for Avoiding Self-Intersection", Ray
// Tracing Gems, ch. 6), not by a fixed epsilon that is too large or too small somewhere.
#ifndef PT_SPAWN_GLSL
#define PT_SPAWN_GLSL

const float kOffsetOrigin = 1.0f / 32.0f;       // near zero, ulps are tiny: offset in floats
const float kOffsetFloatScale = 1.0f / 65536.0f;
const float kOffsetIntScale = 256.0f;

// Near zero, ulps shrink to nothing, so there the offset is a small fraction of the
// scene's size (its bounding radius), not of one unit: tiny scenes need tiny offsets.
float offset_component(float p, float n) {
  int of_i = int(kOffsetIntScale * n);
  float p_i = intBitsToFloat(floatBitsToInt(p) + (p < 0.0f ? -of_i : of_i));
  float size = params.scale.x;
  return abs(p) < kOffsetOrigin * size ? p + kOffsetFloatScale * size * n : p_i;
}

// p: a point on the surface, n: the unit normal on the side the new ray leaves by.
vec3 offset_ray_origin(vec3 p, vec3 n) {
  return vec3(offset_component(p.x, n.x), offset_component(p.y, n.y), offset_component(p.z, n.z));
}

// The ray leaving surface point p in direction dir (n: the surface's geometric normal).
Ray spawn_ray(vec3 p, vec3 n, vec3 dir) {
  vec3 side = dot(dir, n) >= 0.0f ? n : -n;
  return Ray(offset_ray_origin(p, side), dir);
}

#endif  // PT_SPAWN_GLSL
