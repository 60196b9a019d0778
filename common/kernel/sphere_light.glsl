// Sampling a sphere light for stage4's direct light (Eq. 5, corrected by erratum 5) and
// stage5_mis: from outside, a direction uniform in the cone the sphere subtends; from inside
// (or on) it, a point uniform on its area. lights.glsl picks the light and calls these, and
// its light_pdf gives stage5_mis the same densities for a direction a BSDF sample found.

// Part of lights.glsl and included by it alone, inside its include guard: no guard of its
// own (tests/stability/test_float_double.cpp compiles the kernel twice, resetting the guards).

#include "common/kernel/sampling.glsl"
#include "common/kernel/intersect.glsl"
#include "common/kernel/light_sample.glsl"

// From inside (or on) a sphere light: a point uniform on its area, density 1 / (4 pi r^2);
// light reaches the inside only from a double-sided emitter. Its direction from the centre: a
// uniform hemisphere direction drawn with |z|, z = 1 - 2 u.x, mirrored where z < 0.
LightSample sample_sphere_light_inside(Sphere s, vec3 p, vec2 u, float pick) {
  vec3 center = s.center;
  float radius = s.radius;
  float z = 1.0f - 2.0f * u.x;
  vec3 n = sample_uniform_hemisphere(vec2(abs(z), u.y));
  if (z < 0.0f) n.z = -n.z;
  vec3 y = center + radius * n;
  vec3 d = y - p;
  float dist2 = dot(d, d);
  float dist = sqrt(dist2);
  Material m = materials[s.material];
  if (!(dist > 0.0f) || !(m.double_sided != 0u)) return no_light();
  vec3 wi = d / dist;
  float cos_y = abs(dot(wi, n));
  if (!(cos_y > 0.0f)) return no_light();
  float pdf = dist2 / (cos_y * 4.0f * kPi * radius * radius) * pick;
  return LightSample(wi, dist, vec3(m.emission) / pdf, pdf);
}

// Whether p is inside a sphere light, or on its surface within rounding: then the cone
// of directions it subtends is the whole sphere, and its area is sampled instead.
bool inside_sphere_light(Sphere s, vec3 p) {
  vec3 to_center = vec3(s.center) - p;
  return dot(to_center, to_center) <= s.radius * s.radius * 1.001f;
}

// 1 - cos of the half-angle of the cone a sphere subtends from outside, at squared distance
// d2 from its centre: sin^2 / (1 + cos), which keeps the digits that 1 - cos loses for a
// small or distant sphere.
float sphere_cone_one_minus_cos(float radius, float d2) {
  float sin2_max = radius * radius / d2;
  return sin2_max / (1.0f + sqrt(max(0.0f, 1.0f - sin2_max)));
}

// From outside a sphere light: a direction uniform in the cone it subtends, density
// 1 / (2 pi (1 - cos_max)).
LightSample sample_sphere_light(uint index, vec3 p, vec2 u, float pick) {
  Sphere s = spheres[index];
  vec3 center = s.center;
  float radius = s.radius;
  if (inside_sphere_light(s, p)) return sample_sphere_light_inside(s, p, u, pick);
  vec3 to_center = center - p;
  float d2 = dot(to_center, to_center);
  float d = sqrt(d2);
  float one_minus_cos_max = sphere_cone_one_minus_cos(radius, d2);
  float one_minus_cos_t = u.x * one_minus_cos_max;
  float cos_t = 1.0f - one_minus_cos_t;
  float sin_t = sqrt(max(0.0f, one_minus_cos_t * (2.0f - one_minus_cos_t)));
  float phi = 2.0f * kPi * u.y;
  Frame f = make_frame(to_center / d);
  vec3 wi = frame_to_world(f, vec3(sin_t * cos(phi), sin_t * sin(phi), cos_t));
  // Where that direction meets the sphere (the near root).
  float b = dot(to_center, wi);
  float disc = max(0.0f, radius * radius - (d2 - b * b));
  float dist = b - sqrt(disc);
  float pdf = pick / (2.0f * kPi * one_minus_cos_max);
  if (!(pdf > 0.0f) || isinf(pdf)) return no_light();
  return LightSample(wi, dist, vec3(materials[s.material].emission) / pdf, pdf);
}
