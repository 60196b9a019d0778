// Russian roulette, the article's way to end paths without bias (stages 2-4): a path
// continues with probability p and the survivor is divided by p (erratum 3: the printed
// text "adds 1/2 multipliers"; erratum 4: it adds variance, not bias). The article's
// fixed p = 1/2 has infinite variance for albedo above 0.61 with uniform sampling, so
// kRouletteThroughput continues with p = the path weight's largest component instead.
#ifndef PT_ROULETTE_GLSL
#define PT_ROULETTE_GLSL

#include "common/kernel/sampler.glsl"

float max_component(vec3 v) {
  return max(v.x, max(v.y, v.z));
}

bool is_finite(vec3 v) {
  return !any(isnan(v)) && !any(isinf(v));
}

// The roulette's step, declared here and defined in russian_roulette.glsl, or by
// labs/lab2.glsl in lab 2's build (cmake/Labs.cmake): what a surviving path is multiplied
// by (1 / p), or 0 to end it. mode: kRouletteFixed (the article's p = 1/2) or
// kRouletteThroughput (p = min(1, the largest component of beta)).
float russian_roulette(vec3 beta, uint mode);

// The two other ways a path ends, both bookkeeping rather than the article's step, both
// counted for the summary line. The depth cap: a safety net far beyond what roulette
// reaches (--depth-cap).
bool at_depth_cap(uint depth) {
  if (depth != params.depth_cap) return false;
  atomicAdd(counters[kCounterDepthCap], 1u);
  return true;
}

// A sampled direction of zero pdf, or a weight that is not finite, ends the path: never
// divide by a zero pdf.
bool ends_at_zero_pdf(float pdf, vec3 weight) {
  if (pdf > 0.0f && is_finite(weight)) return false;
  atomicAdd(counters[kCounterZeroPdf], 1u);
  return true;
}

#endif  // PT_ROULETTE_GLSL
