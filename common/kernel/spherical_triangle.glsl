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

// A triangle seen from a point: the unit vectors towards its corners and the solid angle
// they span.
struct SphericalTriangle {
  vec3 a;
  vec3 b;
  vec3 c;
  float area;    // solid angle, steradians
  float volume;  // |a . (b x c)|: the volume of the corners' parallelepiped
};

// The triangle p0, p1, p2 seen from p. Its solid angle by Van Oosterom and Strackee:
// tan(omega / 2) = |a . (b x c)| / (1 + a.b + b.c + c.a), accurate for small triangles,
// where the angle excess alpha + beta + gamma - pi loses its digits to the sum near pi.
SphericalTriangle spherical_triangle(vec3 p, vec3 p0, vec3 p1, vec3 p2) {
  vec3 a = normalize(p0 - p);
  vec3 b = normalize(p1 - p);
  vec3 c = normalize(p2 - p);
  float volume = abs(dot(a, cross(b, c)));
  float den = 1.0f + dot(a, b) + dot(b, c) + dot(c, a);
  return SphericalTriangle(a, b, c, 2.0f * atan(volume, den), volume);
}

// A unit vector uniform within the spherical triangle t: u.x chooses the sub-triangle
// a, b, c' of area u.x * t.area (c' on the arc from a to c), u.y a point on the arc from b
// to c' so that the result is uniform (Arvo 1995).
vec3 spherical_triangle_sample(SphericalTriangle t, vec2 u) {
  vec3 a = t.a;
  vec3 b = t.b;
  vec3 c = t.c;
  // The triangle's angle alpha at a lies between the planes through a, b and through a, c,
  // whose normals are n_b = a x b and n_c = a x c: cos alpha = n_b . n_c / (|n_b| |n_c|),
  // and sin alpha = |n_b x n_c| / (|n_b| |n_c|) = |a . (b x c)| / (|n_b| |n_c|), no
  // inverse trigonometry needed.
  vec3 n_b = cross(a, b);
  vec3 n_c = cross(a, c);
  float norms = sqrt(dot(n_b, n_b) * dot(n_c, n_c));
  float cos_alpha = dot(n_b, n_c) / norms;
  float sin_alpha = t.volume / norms;
  // The sub-triangle's area sub = 2h; Arvo's s = sin(sub - alpha), t = cos(sub - alpha),
  // u = t - cos(alpha) and v = s + sin(alpha) cos(c) (cos(c) = a.b) from sin h and cos h
  // by the sum formulas, with 1 - a.b = |a - b|^2 / 2: no difference of nearly equal terms.
  float h = 0.5f * u.x * t.area;
  float sin_h = sin(h);
  float cos_h = cos(h);
  float sin_2h = 2.0f * sin_h * cos_h;
  float cos_2h = 1.0f - 2.0f * sin_h * sin_h;
  float s = sin_2h * cos_alpha - cos_2h * sin_alpha;
  float tt = cos_2h * cos_alpha + sin_2h * sin_alpha;
  float sin_alpha_minus_h = sin_alpha * cos_h - cos_alpha * sin_h;
  float cos_alpha_minus_h = cos_alpha * cos_h + sin_alpha * sin_h;
  float uu = 2.0f * sin_h * sin_alpha_minus_h;
  vec3 ab = a - b;
  float vv = 2.0f * sin_h * cos_alpha_minus_h - sin_alpha * 0.5f * dot(ab, ab);
  // q = cos of the arc from a to c'.
  float q = ((vv * tt - uu * s) * cos_alpha - vv) / ((vv * s + uu * tt) * sin_alpha);
  q = clamp(q, -1.0f, 1.0f);
  vec3 c_perp = normalize(cross(n_c, a));  // the unit tangent at a towards c
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
