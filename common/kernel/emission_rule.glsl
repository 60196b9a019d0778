// Stage4's rule for a hit's own emission (the article's Eq. 5 with erratum 6), declared in
// lights.glsl: once the direct light is sampled at every non-delta hit, an emitter that a
// bounce from such a hit finds was counted already, so its Le (and the sky's) enters the
// sum only where light sampling could not have found it. Lab 4 (docs/labs/lab4.md) asks
// the student for this function with the triangle light: its build compiles labs/lab4.glsl.
#ifndef PT_EMISSION_RULE_GLSL
#define PT_EMISSION_RULE_GLSL

#include "common/kernel/lights.glsl"

// depth: 0 for the camera ray, k after k bounces; after_delta: the last bounce was a
// mirror or glass (a delta lobe, where no light sample is taken).
bool counts_emission(uint depth, bool after_delta) {
  return depth == 0u || after_delta;
}

#endif  // PT_EMISSION_RULE_GLSL
