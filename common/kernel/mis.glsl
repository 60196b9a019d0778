// Multiple importance sampling (Veach and Guibas 1995; Veach's thesis 1997, ch. 9) for
// stage5_mis, beyond the article: a light sample and a BSDF sample estimate the same direct
// light, and each is weighted by the power heuristic (exponent 2) of the two strategies'
// pdfs at its direction, so that the weights of the two sum to 1 wherever either can
// sample, and each strategy counts most where it is the better one. Here: the weight
// (power_heuristic, declared in stage5_mis/integrator.glsl) and the light strategy's pdf of
// a direction that meets an emissive triangle (triangle_light_pdf_by_solid_angle, declared
// in lights.glsl). Lab 6 (docs/labs/lab6.md) asks the student for both: its build compiles
// labs/lab6.glsl instead of this file (cmake/Labs.cmake).
#ifndef PT_MIS_GLSL
#define PT_MIS_GLSL

#include "common/kernel/lights.glsl"

// The power heuristic's weight of a sample drawn with pdf `mine`, where the other strategy
// would have drawn its direction with pdf `other` (one sample from each): mine^2 /
// (mine^2 + other^2), as 1 / (1 + (other / mine)^2), which neither overflows for the huge
// pdfs of sharp lobes and tiny lights nor divides 0 by 0.
float power_heuristic(float mine, float other) {
  if (!(mine > 0.0f)) return 0.0f;
  float r = other / mine;
  return 1.0f / (1.0f + r * r);
}

// What sample_light_by(p, n, kTriangleBySolidAngle) does for the triangle, run backwards:
// the same facing test, the same solid angle and the same choice between solid angle and
// area (sample_by_solid_angle), so that the light sample's pdf and this one are the same
// number, bit for bit.
float triangle_light_pdf_by_solid_angle(uint index, vec3 p, vec3 wi, float dist) {
  Triangle tri = triangles[index];
  if (tri.light == kNoLight || !triangle_lights_point(tri, p)) return 0.0f;
  SphericalTriangle t = spherical_triangle(p, vec3(tri.p0), vec3(tri.p1), vec3(tri.p2));
  if (!sample_by_solid_angle(t)) return triangle_light_pdf(index, wi, dist);
  return light_pick_probability(tri.light) / t.area;
}

#endif  // PT_MIS_GLSL
