// Russian roulette's step for stages 2-5 (the article's section on Eq. 3, errata 3 and 4),
// declared in roulette.glsl: continue with probability p, and divide the survivor by p so
// that the expected value stays the same. Lab 2 (docs/labs/lab2.md) asks the student for
// this function with the uniform estimator: its build compiles labs/lab2.glsl instead.
#ifndef PT_RUSSIAN_ROULETTE_GLSL
#define PT_RUSSIAN_ROULETTE_GLSL

#include "common/kernel/roulette.glsl"

// Returns what a surviving path is multiplied by (1 / p), or 0 to end it.
float russian_roulette(vec3 beta, uint mode) {
  float p = mode == kRouletteFixed ? 0.5f : min(1.0f, max_component(beta));
  if (!(p > 0.0f) || sample_1d() >= p) return 0.0f;
  return 1.0f / p;
}

#endif  // PT_RUSSIAN_ROULETTE_GLSL
