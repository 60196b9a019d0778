// Lab 6 (docs/labs/lab6.md): multiple importance sampling in stage5_mis, beyond the article
// (docs/stage5_mis.md). Write the power heuristic that weighs a light sample and a BSDF
// sample of the same direct light, and the light strategy's pdf of a direction that a BSDF
// sample found on an emissive triangle (light_pdf's triangle part): the pdf that the light
// sample by solid angle would have drawn it with. Built instead of common/kernel/mis.glsl
// when you configure with -DPT_LAB=6. Graded by `ctest -L lab6`.
// Written in the GLSL/C++ subset (docs/README.md): it runs on both backends.

#include "labs/lab_support.glsl"
#include "common/kernel/lights.glsl"

// mine: the pdf (solid angle) with which this sample's strategy drew its direction; other:
// the pdf with which the other strategy would have drawn that same direction. Return the
// power heuristic's weight (exponent 2): mine^2 / (mine^2 + other^2), in [0, 1]. It must
// never be NaN: return 0 when mine is 0, and keep the answer right for pdfs up to 3e38
// (mine^2 overflows to infinity from about 1.8e19) and down to the smallest subnormals
// (whose square is 0).
float power_heuristic(float mine, float other) {
  // Your code here. Remove the line below when you are done.
  return PT_LAB_NOT_WRITTEN(6, power_heuristic) * mine * other;
}

// index: the triangle a BSDF sample's ray from p met (triangles[index]), in direction wi
// (unit) at distance dist. Return the pdf (solid angle, times the probability of picking
// this light) with which sample_light_by(p, n, kTriangleBySolidAngle) would have drawn wi:
// 0 if the triangle is no light (tri.light == kNoLight) or does not light p
// (triangle_lights_point); where the light sample falls back to the triangle's area
// (!sample_by_solid_angle of the triangle seen from p), the area pdf triangle_light_pdf;
// else the pick probability over the solid angle. It must decide exactly as the sampler
// (sample_triangle_light_by_solid_angle in lights.glsl) does, from the same numbers.
float triangle_light_pdf_by_solid_angle(uint index, vec3 p, vec3 wi, float dist) {
  // Your code here. Remove the lines below when you are done.
  float nan = PT_LAB_NOT_WRITTEN(6, triangle_light_pdf_by_solid_angle) * dist;
  return nan * float(index) * dot(p, wi);
}
