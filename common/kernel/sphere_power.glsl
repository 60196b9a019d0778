// The power of a ray origin with respect to a sphere, the constant term of hit_sphere()'s
// quadratic (common/kernel/intersect.glsl; the article's raycasting step, Eq. 2), in the
// form that rounds least for spheres far from the world origin. Uses vec3 and float alone,
// so that the CPU's sphere arrays (cpu/sphere_soa.cpp) compute the same terms with it.
#ifndef PT_SPHERE_POWER_GLSL
#define PT_SPHERE_POWER_GLSL

// The terms of sphere_power_from_world_origin() that depend on the sphere alone: the CPU
// keeps them per sphere (cpu/sphere_soa.cpp) for its SIMD lanes (cpu/sphere_lanes.h); the
// GPU computes them per ray. m is the centre's largest coordinate, in absolute value.
struct SpherePowerTerms {
  vec3 abs_center;    // the centre's coordinates in absolute value
  float center_power; // |centre|^2 - r^2, as lead + others
  float lead_abs;     // |lead|, lead = (m - r)(m + r)
  float others;       // the centre's two other coordinates squared
};

SpherePowerTerms sphere_power_terms(vec3 center, float radius) {
  vec3 a = abs(center);
  float m = a.z;
  float others = a.x * a.x + a.y * a.y;
  if (a.x >= a.y && a.x >= a.z) {
    m = a.x;
    others = a.y * a.y + a.z * a.z;
  } else if (a.y >= a.z) {
    m = a.y;
    others = a.x * a.x + a.z * a.z;
  }
  float lead = (m - radius) * (m + radius);
  return SpherePowerTerms(a, lead + others, abs(lead), others);
}

// The power of the ray origin o with respect to the sphere, |o - centre|^2 - r^2 (< 0
// inside; the product of the distances to the two roots), written from the world origin:
// |o|^2 - 2 o.centre + (|centre|^2 - r^2), the last term as (m - r)(m + r) plus the other
// two coordinates squared, m the centre's largest coordinate. Returns the power and the
// size of the numbers summed for it, the scale of its rounding error. smallpt's walls have
// centres 1e5 away and the room near the world origin: there f = o - centre is known only
// to 1/128 per coordinate, this form to the rounding of o.centre (1e7: about 1), since
// m - r is exact for m near r. A small sphere far from the world origin is the other way.
vec2 sphere_power_from_world_origin(vec3 o, vec3 center, float radius) {
  SpherePowerTerms s = sphere_power_terms(center, radius);
  float oo = dot(o, o);
  float power = (oo + s.center_power) - 2.0f * dot(o, center);
  float scale = oo + 2.0f * dot(abs(o), s.abs_center) + s.lead_abs + s.others;
  return vec2(power, scale);
}

#endif  // PT_SPHERE_POWER_GLSL
