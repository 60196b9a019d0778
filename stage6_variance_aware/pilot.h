// stage6_variance_aware's pilot, the host's side (beyond the article; docs/stage6_variance_aware.md,
// "Weights from a pilot"): a small image of the same view, rendered before the render with its
// own seeds, that measures how well each of the two strategies, the light sample and the BSDF
// sample, estimates the direct light at the scene's diffuse and at its glossy vertices under
// the render's own sampler (mis_pilot.glsl). The ratio of their errors sets the factor on the
// light pdf in the MIS weights: the power heuristic with each strategy counted in inverse
// proportion to its variance, as variance-aware MIS (Grittmann et al. 2019) counts them. Any
// factor keeps the estimator unbiased (the two weights still sum to 1 at every direction); the
// pilot only chooses one that keeps its variance low. It is the stage's before-render step
// (pt::BeforeRender, common/render/backend.h).
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include <glm/glm.hpp>

#include "common/render/backend.h"

namespace stage6 {

// The factors are powers of two within these bounds: a factor of 2^8 leaves the other
// strategy at most 2^-16 of its power-heuristic share, as good as none, and powers of two
// make the CPU's and the GPU's pilots, whose sums differ in their last bits, choose the same.
inline constexpr float kMisScaleMin = 1.0f / 256.0f;
inline constexpr float kMisScaleMax = 256.0f;

// The pilot's image: the view at most this many pixels on its longer side, and its samples
// per pixel in each of its two renders (one pass each).
inline constexpr int kMisPilotSide = 32;
inline constexpr std::uint32_t kMisPilotSpp = 16;

// One lobe class's pilot, summed over its pixels: (first render's mean - second's)^2 / 2 of
// the light strategy's estimate and of the BSDF strategy's, each an estimate of the variance
// of that pixel's estimate under the render's sampler (the two renders are independent).
struct MisPilotErrors {
  double light = 0.0, bsdf = 0.0;
};

// The factor for one class: bsdf / light rounded to a power of two within the bounds; 1
// where the pilot saw no direct light of that class (both 0) or numbers that are not finite,
// the bound where one strategy's error is 0 (it is then exact there).
float mis_scale_from(const MisPilotErrors& errors);

struct MisScales {
  float diffuse = 1.0f, glossy = 1.0f;
  int width = 0, height = 0;  // the pilot's image
};

// Runs the pilot on `backend` (its scene set) with the render's `params` (the pilot sets its
// own image size, seeds, samples and mode), into `buffer` (at least the pilot's pixels);
// `glossy`: the scene has glossy lobes, else their class keeps the factor 1.
MisScales measure_mis_scales(pt::Backend& backend, pt::FrameParams params, bool glossy, std::span<glm::vec4> buffer);

// The stage's before-render step: the pilot, its factors as FrameParams::stage_params
// (.y, .z: their log2 at diffuse and glossy vertices) and its note for the summary line.
pt::StageTuning run_pilot(pt::Backend& backend, const pt::FrameParams& params, pt::uint features,
                          std::span<glm::vec4> buffer);

// For the summary line: "[mis pilot: 32x32, light pdf x16 at diffuse, x1 at glossy vertices]".
std::string mis_summary(const MisScales& scales);

}  // namespace stage6
