// Spherical triangles, for light sampling by solid angle (stage5_mis, beyond the article):
// the solid angle a triangle subtends from a point (Van Oosterom and Strackee 1983) and a
// direction uniform within it (Arvo, "Stratified Sampling of Spherical Triangles",
// SIGGRAPH 1995), so that a light sample's pdf is the constant 1 / solid angle. Arvo's
// formulas are rewritten here without the differences of nearly equal numbers that make
// them lose precision on small triangles (spherical_triangle_sample says how).
#ifndef PT_SPHERICAL_TRIANGLE_GLSL
#define PT_SPHERICAL_TRIANGLE_GLSL

#include "common/kernel/sampling.glsl"
#include "common/kernel/float_math.glsl"

// Solid angles between these bounds are sampled by spherical_triangle_sample; outside them
// the light falls back to sampling its area (lights.glsl). Between them the float mapping
// keeps its density within 1e-4 of 1 / solid angle (at worst 5e-5, for slivers of 1e-3 sr,
// measured against long double: the chi-square and CDF tests of
// tests/common/kernel/test_spherical_triangle.cpp). A smaller triangle is far enough that
// area sampling's 1 / d^2 hardly varies over it; near the 2 pi of a whole hemisphere the
// corners are nearly opposite each other and the mapping's square roots lose their digits.
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
// a . (b x c) is taken as a . ((b - a) x (c - a)), the same number, whose cross product
// of two short differences keeps its digits when the corners are close together.
SphericalTriangle spherical_triangle(vec3 p, vec3 p0, vec3 p1, vec3 p2) {
  vec3 a = normalize(p0 - p);
  vec3 b = normalize(p1 - p);
  vec3 c = normalize(p2 - p);
  float volume = abs(dot(a, cross(b - a, c - a)));
  float den = 1.0f + dot(a, b) + dot(b, c) + dot(c, a);
  return SphericalTriangle(a, b, c, 2.0f * atan2_upper(volume, den), volume);
}

// A unit vector uniform within the spherical triangle t (Arvo 1995): u.x chooses the
// sub-triangle a, b, c' of area u.x * t.area, with c' on the arc from a to c, and u.y a
// point on the arc from b to c' so that the result is uniform. Arvo finds c' through the
// cosine q of the arc from a to c'; in float, q sits so close to 1 for a small triangle
// that one unit in its last place moves c' by 3.5e-4 rad, more than such a triangle is
// wide (the chi-square test of tests/common/kernel/test_spherical_triangle.cpp failed at
// 1e-3 sr). Here c' comes from x = tan of half that arc instead, by the area of a
// spherical triangle with sides b', c and the angle alpha between them,
// tan(area / 2) = x k sin(alpha) / (1 + x k cos(alpha)), k = tan(c / 2), solved for x:
// x = sin(h) / (k sin(alpha - h)) with h = area / 2, which no rounding near 1 disturbs.
vec3 spherical_triangle_sample(SphericalTriangle t, vec2 u) {
  vec3 a = t.a;
  vec3 b = t.b;
  vec3 ba = t.b - t.a;
  vec3 ca = t.c - t.a;
  // The angle alpha at a lies between the planes through a, b and through a, c, whose
  // normals are n_b = a x b and n_c = a x c (taken of the differences, the same vectors):
  // cos alpha = n_b . n_c / (|n_b| |n_c|), sin alpha = |a . (b x c)| / (|n_b| |n_c|).
  vec3 n_b = cross(a, ba);
  vec3 n_c = cross(a, ca);
  float norms = sqrt(dot(n_b, n_b) * dot(n_c, n_c));
  float cos_alpha = dot(n_b, n_c) / norms;
  float sin_alpha = t.volume / norms;
  float h = 0.5f * u.x * t.area;
  vec2 sc = sin_cos(h);  // float_math.glsl: the built-ins are not precise enough on GPUs
  float sin_h = sc.x;
  float cos_h = sc.y;
  float k = length(ba) / length(a + b);  // tan(c / 2), c the arc from a to b
  float x = sin_h / (k * (sin_alpha * cos_h - cos_alpha * sin_h));
  // cos and sin of the arc b' = 2 atan(x) from a to c'; x beyond float: b' = pi.
  float cos_arc = -1.0f;
  float sin_arc = 0.0f;
  if (x < 1e30f) {
    cos_arc = (1.0f - x * x) / (1.0f + x * x);
    sin_arc = 2.0f * x / (1.0f + x * x);
  }
  vec3 c_perp = normalize(cross(n_c, a));  // the unit tangent at a towards c
  vec3 c_sub = cos_arc * a + sin_arc * c_perp;
  // z = 1 - u.y (1 - c'.b): the cosine of the angle from b, uniform in area between b and
  // c', with 1 - c'.b = |c' - b|^2 / 2; and c' - (c'.b) b = (c' - b) + (1 - c'.b) b.
  vec3 cb = c_sub - b;
  float one_minus_cb = 0.5f * dot(cb, cb);
  float one_minus_z = u.y * one_minus_cb;
  float z = 1.0f - one_minus_z;
  vec3 to_c = cb + one_minus_cb * b;
  float to_c_length = length(to_c);
  if (!(to_c_length > 0.0f)) return b;  // c' = b: the sub-triangle is a point
  return z * b + sqrt(max(0.0f, one_minus_z * (2.0f - one_minus_z))) * (to_c / to_c_length);
}

#endif  // PT_SPHERICAL_TRIANGLE_GLSL
