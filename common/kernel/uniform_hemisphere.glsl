// The uniform hemisphere sampler of stage2 (the article's Eq. 3), its pdf, and the weight
// (2 pi / N) f cos of Eq. (3) that a bounce multiplies the path by, declared in
// sampling.glsl. Lab 2 (docs/labs/lab2.md) asks the student for these three functions and
// for the roulette (russian_roulette.glsl): its build compiles labs/lab2.glsl instead.
#ifndef PT_UNIFORM_HEMISPHERE_GLSL
#define PT_UNIFORM_HEMISPHERE_GLSL

#include "common/kernel/sampling.glsl"

// Uniform over the hemisphere z > 0: cos(theta) = u.x, phi = 2 pi u.y; pdf 1 / (2 pi).
vec3 sample_uniform_hemisphere(vec2 u) {
  float z = u.x;
  float r = sqrt(max(0.0f, 1.0f - z * z));
  float phi = 2.0f * kPi * u.y;
  return vec3(r * cos(phi), r * sin(phi), z);
}

float uniform_hemisphere_pdf() {
  return 1.0f / (2.0f * kPi);
}

// Eq. (3) with N = 1, corrected (erratum 1: the article prints 1 / (2 pi N)): the BRDF
// value f of the sampled direction wi (local frame, z = cos theta), times cos theta,
// divided by the pdf of drawing wi, 1 / (2 pi).
vec3 uniform_bounce_weight(vec3 f, vec3 wi) {
  return f * (wi.z / uniform_hemisphere_pdf());
}

#endif  // PT_UNIFORM_HEMISPHERE_GLSL
