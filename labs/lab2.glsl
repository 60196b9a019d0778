// Lab 2 (docs/labs/lab2.md): the Monte Carlo estimator of the article's Eq. (3) with its
// corrected factor 2 pi / N (erratum 1). Write the uniform hemisphere sampler, its pdf, the
// weight a bounce multiplies the path by, and Russian roulette's step. Built instead of the
// real functions of common/kernel/uniform_hemisphere.glsl and russian_roulette.glsl when
// you configure with -DPT_LAB=2. Graded by `ctest -L lab2`.
// Written in the GLSL/C++ subset (docs/README.md): it runs on both backends.

#include "labs/lab_support.glsl"
#include "common/kernel/sampling.glsl"
#include "common/kernel/roulette.glsl"

// u: two independent numbers uniform in [0, 1). Return a unit direction (x, y, z) with
// z > 0 (z is the cosine to the normal), uniform over the hemisphere: its density in solid
// angle must be the same everywhere.
vec3 sample_uniform_hemisphere(vec2 u) {
  // Your code here. Remove the line below when you are done.
  return vec3(PT_LAB_NOT_WRITTEN(2, sample_uniform_hemisphere)) * u.x;
}

// The density of sample_uniform_hemisphere in solid angle (per steradian).
float uniform_hemisphere_pdf() {
  // Your code here. Remove the line below when you are done.
  return PT_LAB_NOT_WRITTEN(2, uniform_hemisphere_pdf);
}

// One bounce of Eq. (3) with N = 1: f is the BRDF's value for the direction wi you sampled
// (local frame: wi.z is cos theta). Return what stage2 multiplies the path's weight by, so
// that on average the bounce carries the integral of f Lin cos over the hemisphere.
vec3 uniform_bounce_weight(vec3 f, vec3 wi) {
  // Your code here. Remove the line below when you are done.
  return vec3(PT_LAB_NOT_WRITTEN(2, uniform_bounce_weight)) * f * wi.z;
}

// Russian roulette: decide whether the path goes on, with probability p, and return what
// the path's weight beta is then multiplied by, or 0.0f to end it. Draw the one uniform
// number you need with sample_1d(). mode is kRouletteFixed (the article's p = 1/2) or
// kRouletteThroughput (p = min(1, the largest component of beta): max_component(beta)).
float russian_roulette(vec3 beta, uint mode) {
  // Your code here. Remove the line below when you are done.
  return PT_LAB_NOT_WRITTEN(2, russian_roulette) * beta.x * float(mode);
}
