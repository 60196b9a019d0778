// Multiple importance sampling (Veach and Guibas 1995; Veach's thesis 1997, ch. 9) for
// stage5_mis, beyond the article: a light sample and a BSDF sample estimate the same direct
// light, and each is weighted by the power heuristic (exponent 2) of the two strategies'
// pdfs at its direction, so that the weights of the two sum to 1 wherever either can
// sample, and each strategy counts most where it is the better one.
#ifndef PT_MIS_GLSL
#define PT_MIS_GLSL

// The power heuristic's weight of a sample drawn with pdf `mine`, where the other strategy
// would have drawn its direction with pdf `other` (one sample from each): mine^2 /
// (mine^2 + other^2), as 1 / (1 + (other / mine)^2), which neither overflows for the huge
// pdfs of sharp lobes and tiny lights nor divides 0 by 0.
float power_heuristic(float mine, float other) {
  if (!(mine > 0.0f)) return 0.0f;
  float r = other / mine;
  return 1.0f / (1.0f + r * r);
}

#endif  // PT_MIS_GLSL
