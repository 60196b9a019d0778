// Starting a new ray from a surface without hitting that surface again ("acne") and
// without slipping through a neighbouring one ("light leaks"), at any scene scale: the
// origin moves off the surface by a few units in the last place of its own coordinates
// (Wächter and Binder, "A Fast and Robust Method for Avoiding Self-Intersection", Ray
// Tracing Gems, ch. 6), not by a fixed epsilon that is too large or too small somewhere.
#ifndef PT_SPAWN_GLSL
#define PT_SPAWN_GLSL

#include "common/kernel/camera.glsl"

// The spacing of floats just above x >= 0: how finely a coordinate of that size is known.
float ulp_above(float x) {
  return intBitsToFloat(floatBitsToInt(x) + 1) - x;
}

// The surface point's error, and so the height the new origin clears the surface by, in
// units in the last place of its coordinates (kOffsetUlps ulps in each coordinate, seen
// along the normal: sum |n_i| ulp(p_i)). Few ulps, so that far from the origin the offset
// stays below a small scene's own features; summed over the coordinates, so that a normal
// along one axis still clears the error of the others (docs/stability.md has the numbers).
const float kOffsetUlps = 8.0f;

// Near zero ulps shrink to nothing, but a point there is known only as well as the
// vertices it was interpolated from: coordinates count as at least kOffsetSceneScale
// times the scene's radius (8 ulps of that are 1.5e-5 radii).
const float kOffsetSceneScale = 16.0f;

float offset_height(vec3 p, vec3 n) {
  float size = kOffsetSceneScale * params.scene_radius;
  return kOffsetUlps * (abs(n.x) * ulp_above(max(abs(p.x), size)) + abs(n.y) * ulp_above(max(abs(p.y), size)) +
                        abs(n.z) * ulp_above(max(abs(p.z), size)));
}

// p: a point on the surface, n: the unit normal on the side the new ray leaves by.
vec3 offset_ray_origin(vec3 p, vec3 n) {
  return p + offset_height(p, n) * n;
}

// Below this |cos| between the new ray and the normal, the origin moves partly off the ray.
const float kAlongRayMinCos = 0.25f;

// The ray leaving surface point p in direction dir (n: the surface's geometric normal).
// The origin must clear the surface by the height h; reaching that height by moving along
// the ray itself (t = h / cos) keeps the ray on its line from p, so what it meets is what
// a ray from p meets beyond t. An origin shifted sideways by h instead sees the scene
// from the wrong place: 8 ulps at 1e5 are 0.06 units, 6% of a light 1 unit above the
// floor, and stage3 (which finds lights with such rays) rendered that floor 4% too bright.
// Grazing rays (cos < kAlongRayMinCos) would move too far along: they take the rest of h
// from the normal offset.
Ray spawn_ray(vec3 p, vec3 n, vec3 dir) {
  vec3 side = dot(dir, n) >= 0.0f ? n : -n;
  float h = offset_height(p, side);
  float c = abs(dot(dir, n));
  float along = c >= kAlongRayMinCos ? h / c : h / kAlongRayMinCos;
  float normal_part = c >= kAlongRayMinCos ? 0.0f : h * (1.0f - c / kAlongRayMinCos);
  // Rounding each coordinate costs at most h / (2 kOffsetUlps) of the height.
  return Ray(p + along * dir + normal_part * side, dir);
}

#endif  // PT_SPAWN_GLSL
