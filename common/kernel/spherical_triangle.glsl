// Spherical triangles, for light sampling by solid angle (stage5_mis, beyond the article):
// the solid angle a triangle subtends from a point (Van Oosterom and Strackee 1983) and a
// direction uniform within it (Arvo, "Stratified Sampling of Spherical Triangles",
// SIGGRAPH 1995), so that a light sample's pdf is the constant 1 / solid angle. Arvo's
// formulas are rewritten here without the differences of nearly equal numbers that make
// them lose precision on small triangles (the comments give the original terms).
#ifndef PT_SPHERICAL_TRIANGLE_GLSL
#define PT_SPHERICAL_TRIANGLE_GLSL

#include "common/kernel/sampling.glsl"

// Solid angles between these bounds are sampled by spherical_triangle_sample; outside them
// the light falls back to sampling its area (lights.glsl). Below the lower bound, a float
// Arvo mapping no longer keeps its density within 1e-4 of 1 / solid angle (the chi-square
// and pdf tests of tests/common/kernel/test_spherical_triangle.cpp), and a triangle that
// small is far enough that area sampling's 1 / d^2 hardly varies over it; above the upper
// bound (close to the 2 pi of a whole hemisphere) the triangle's corners are nearly
// opposite each other and the mapping's square roots lose their digits.
const float kMinSphericalTriangle = 1e-3f;
const float kMaxSphericalTriangle = 6.2f;

// The angle between two unit vectors, accurate near 0 and near pi (where acos is not).
float angle_between(vec3 a, vec3 b) {
  if (dot(a, b) < 0.0f) return kPi - 2.0f * asin(min(0.5f * length(a + b), 1.0f));
  return 2.0f * asin(min(0.5f * length(a - b), 1.0f));
}

// The solid angle of the spherical triangle of unit vectors a, b, c:
// tan(omega / 2) = |a . (b x c)| / (1 + a.b + b.c + c.a).
float spherical_triangle_area(vec3 a, vec3 b, vec3 c) {
  float volume = abs(dot(a, cross(b, c)));
  float den = 1.0f + dot(a, b) + dot(b, c) + dot(c, a);
  return 2.0f * atan(volume, den);
}

// A unit vector uniform within the spherical triangle a, b, c (unit vectors) whose solid
// angle is `area`: u.x chooses the sub-triangle a, b, c' of area u.x * area (c' on the arc
// from a to c), u.y a point on the arc from b to c' so that the result is uniform.
vec3 spherical_triangle_sample(vec3 a, vec3 b, vec3 c, float area, vec2 u) {
  // The triangle's angle at a: between the planes through a, b and through a, c.
  float alpha = angle_between(normalize(cross(a, b)), normalize(cross(a, c)));
  float sub = u.x * area;
  float half_sub = 0.5f * sub;
  float s = sin(sub - alpha);
  float t = cos(sub - alpha);
  // Arvo's u = t - cos(alpha) and v = s + sin(alpha) cos(c), where cos(c) = a.b, by the sum
  // formulas and 1 - a.b = |a - b|^2 / 2.
  float uu = 2.0f * sin(half_sub) * sin(alpha - half_sub);
  vec3 ab = a - b;
  float vv = 2.0f * sin(half_sub) * cos(alpha - half_sub) - sin(alpha) * 0.5f * dot(ab, ab);
  // q = cos of the arc from a to c'.
  float q = ((vv * t - uu * s) * cos(alpha) - vv) / ((vv * s + uu * t) * sin(alpha));
  q = clamp(q, -1.0f, 1.0f);
  vec3 c_perp = normalize(cross(cross(a, c), a));  // the unit tangent at a towards c
  vec3 c_sub = q * a + sqrt(max(0.0f, (1.0f - q) * (1.0f + q))) * c_perp;
  // z = 1 - u.y (1 - c'.b): the cosine of the angle from b, uniform in area between b and c'.
  vec3 cb = c_sub - b;
  float one_minus_z = u.y * 0.5f * dot(cb, cb);
  float z = 1.0f - one_minus_z;
  vec3 to_c = c_sub - dot(c_sub, b) * b;
  float to_c_length = length(to_c);
  if (!(to_c_length > 0.0f)) return b;  // c' = b: the sub-triangle is a point
  return z * b + sqrt(max(0.0f, one_minus_z * (2.0f - one_minus_z))) * (to_c / to_c_length);
}

#endif  // PT_SPHERICAL_TRIANGLE_GLSL
