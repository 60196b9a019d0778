// The cosine-weighted hemisphere sampler of stage3 (the article's Eq. 4) and its pdf,
// declared in sampling.glsl. Lab 3 (docs/labs/lab3.md) asks the student for these two
// functions: its build compiles labs/lab3.glsl instead of this file.
#ifndef PT_COSINE_HEMISPHERE_GLSL
#define PT_COSINE_HEMISPHERE_GLSL

#include "common/kernel/sampling.glsl"

// Cosine-weighted over the hemisphere z > 0 (Malley's method: uniform on the disk, lifted
// up): pdf cos(theta) / pi, the diffuse lobe's own shape (stage3, Eq. 4).
vec3 sample_cosine_hemisphere(vec2 u) {
  float r = sqrt(u.x);
  float phi = 2.0f * kPi * u.y;
  return vec3(r * cos(phi), r * sin(phi), sqrt(max(0.0f, 1.0f - u.x)));
}

float cosine_hemisphere_pdf(float cos_theta) {
  return max(cos_theta, 0.0f) * (1.0f / kPi);
}

#endif  // PT_COSINE_HEMISPHERE_GLSL
