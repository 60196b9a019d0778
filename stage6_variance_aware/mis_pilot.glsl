// stage6_variance_aware's pilot, the kernel's side (beyond the article; variance-aware MIS,
// Grittmann, Georgiev, Slusallek and Křivánek 2019; docs/stage6_variance_aware.md). The power
// heuristic compares the two strategies' pdfs at a direction, which says how densely each
// samples there, not how well it estimates: under one quad light over a diffuse floor the
// light sample, drawn by solid angle, is a smooth function of its random numbers that the
// Sobol points integrate far faster than N^-1/2, while the BSDF sample finds the light or
// misses it. Before the render a small image of the same view runs Li in pilot mode
// (params.stage_params.x = 1 + the lobe class measured): the vertices of that class add up, in
// luminance, what each strategy alone would have found there (the light sample's direct light
// X_l, the BSDF sample's emission X_b, each unweighted, times the path's throughput). The host
// (pilot.cpp) compares two independent pilots' sums to get each strategy's error and sets the
// light pdf's factor in the weights (log2 in stage_params.y at diffuse, .z at glossy vertices).
// Written in the GLSL/C++ subset: both backends run this file.
#ifndef PT_STAGE6_MIS_PILOT_GLSL
#define PT_STAGE6_MIS_PILOT_GLSL

#include "common/kernel/color.glsl"

// The lobe classes the pilot measures apart (stage_params.x = 1 + class).
const uint kMisClassDiffuse = 0u;
const uint kMisClassGlossy = 1u;

uint mis_class(uint lobe) {
  return lobe == kMaterialConductor || lobe == kMaterialDielectric || lobe == kMaterialRoughGlass ? kMisClassGlossy
                                                                                                  : kMisClassDiffuse;
}

// The pilot mode of this pass: 0 renders the image, 1 + class measures that lobe class.
uint pilot_mode() {
  return uint(params.stage_params.x);
}

// The light pdf's factor in the weights at a vertex of this lobe: 2^(the pilot's log2), 1
// (Veach's power heuristic) where no pilot ran.
float mis_light_scale(uint lobe) {
  return exp2(mis_class(lobe) == kMisClassGlossy ? params.stage_params.z : params.stage_params.y);
}

// One path's sums of X_l and X_b, and the X_l of the vertex whose BSDF sample is in flight.
struct MisPilot {
  vec3 sums;        // the sum of X_l, the sum of X_b, 0
  float pending_l;  // X_l of that vertex
  bool pending;     // a vertex of the class measured waits for its BSDF sample's X_b
};

MisPilot mis_pilot_start() {
  return MisPilot(vec3(0.0f), 0.0f, false);
}

// A non-delta vertex of lobe `lobe`, whose light sample found x_l (0 if none, occluded or
// facing away); its BSDF sample's X_b follows (mis_pilot_found).
MisPilot mis_pilot_vertex(MisPilot pilot, uint lobe, vec3 x_l) {
  if (pilot_mode() == 0u || mis_class(lobe) + 1u != pilot_mode()) return pilot;
  return MisPilot(pilot.sums, luminance(x_l), true);
}

// The emission x_b (0 if none) that the BSDF sample of the last vertex found.
MisPilot mis_pilot_found(MisPilot pilot, vec3 x_b) {
  if (!pilot.pending) return pilot;
  return MisPilot(pilot.sums + vec3(pilot.pending_l, luminance(x_b), 0.0f), 0.0f, false);
}

#endif  // PT_STAGE6_MIS_PILOT_GLSL
