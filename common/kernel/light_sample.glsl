// What a light sample is (stage4's Eq. 5 and stage5_mis's light strategy): the direction
// towards a point chosen on a light, its distance, and the light's radiance over the pdf
// of that choice. Every light kind's sampler returns one (lights.glsl, punctual_light.glsl,
// triangle_light.glsl).
#ifndef PT_LIGHT_SAMPLE_GLSL
#define PT_LIGHT_SAMPLE_GLSL

struct LightSample {
  vec3 wi;         // unit direction from the shading point towards the light
  float dist;      // distance to the light point (kInfinity for the sky)
  vec3 weight;     // Le / (pdf_solid_angle x pick probability); 0 when nothing is lit
  float pdf;       // pdf_solid_angle x pick probability (0 for delta lights)
};

LightSample no_light() {
  return LightSample(vec3(0.0f, 0.0f, 1.0f), 0.0f, vec3(0.0f), 0.0f);
}

#endif  // PT_LIGHT_SAMPLE_GLSL
