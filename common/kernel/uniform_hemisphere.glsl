// The uniform hemisphere sampler of stage2 (the article's Eq. 3) and its pdf, declared in
// sampling.glsl. Lab 2 (docs/labs/lab2.md) asks the student for these two functions: its
// build compiles labs/lab2.glsl instead of this file.
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

#endif  // PT_UNIFORM_HEMISPHERE_GLSL
