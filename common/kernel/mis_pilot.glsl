// stage5_mis's pilot (beyond the article): how well each of its two strategies estimates
// the direct light in this scene, so that the MIS weights can count the better one more
// (variance-aware MIS, Grittmann, Georgiev, Slusallek and Křivánek 2019; docs/stage5_mis.md,
// "Weights from a pilot"). The power heuristic compares the two pdfs at a direction, which
// says how densely each strategy samples there, not how well it estimates: under one quad
// light over a diffuse floor the light sample, drawn by solid angle, is a smooth function of
// its random numbers that the Sobol points integrate far faster than N^-1/2, while the BSDF
// sample finds the light or misses it; in a box whose walls all glow, every BSDF sample finds
// emission and the light sample picks one wall triangle by area. Before the render a small
// image of the same view (its own seed: the render's samples do not depend on it) runs Li
// with params.pilot set, and the vertices of the lobe class asked for add up, in luminance,
// what each strategy alone would have found there (the light sample's direct light X_l, the
// BSDF sample's emission X_b, each unweighted, times the path's throughput): each pixel's
// two estimates of the same direct light. The host (common/render/mis_pilot.cpp) takes each
// estimate's error from the two halves of the pilot's samples, as the film does (film.h),
// so the error is that of these points, not of independent ones, and sets the factor on the
// light pdf (params.mis_diffuse, params.mis_glossy) from their ratio.
// Written in the GLSL/C++ subset: both backends run this file.
#ifndef PT_MIS_PILOT_GLSL
#define PT_MIS_PILOT_GLSL

#include "common/kernel/color.glsl"

// The lobe classes the pilot measures apart (params.pilot = 1 + class).
const uint kMisClassDiffuse = 0u;
const uint kMisClassGlossy = 1u;

uint mis_class(uint lobe) {
  return lobe == kMaterialConductor || lobe == kMaterialDielectric || lobe == kMaterialRoughGlass ? kMisClassGlossy
                                                                                                  : kMisClassDiffuse;
}

// The light pdf's factor in the weights at a vertex of this lobe (1 outside stage5's renders).
float mis_light_scale(uint lobe) {
  return mis_class(lobe) == kMisClassGlossy ? params.mis_glossy : params.mis_diffuse;
}

// One path's sums of X_l and X_b, and the X_l of the vertex whose BSDF sample is in flight.
struct MisPilot {
  vec3 sums;        // the sum of X_l, the sum of X_b, 0
  float pending_l;  // X_l of that vertex
  bool pending;     // a vertex of the class asked for waits for its BSDF sample's X_b
};

MisPilot mis_pilot_start() {
  return MisPilot(vec3(0.0f), 0.0f, false);
}

// A non-delta vertex of lobe `lobe`, whose light sample found x_l (0 if none, occluded or
// facing away); its BSDF sample's X_b follows (mis_pilot_found).
MisPilot mis_pilot_vertex(MisPilot pilot, uint lobe, vec3 x_l) {
  if (params.pilot == 0u || mis_class(lobe) + 1u != params.pilot) return pilot;
  return MisPilot(pilot.sums, luminance(x_l), true);
}

// The emission x_b (0 if none) that the BSDF sample of the last vertex found.
MisPilot mis_pilot_found(MisPilot pilot, vec3 x_b) {
  if (!pilot.pending) return pilot;
  return MisPilot(pilot.sums + vec3(pilot.pending_l, luminance(x_b), 0.0f), 0.0f, false);
}

#endif  // PT_MIS_PILOT_GLSL
