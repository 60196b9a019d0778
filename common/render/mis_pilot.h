// stage5_mis's pilot (beyond the article; docs/stage5_mis.md, "Weights from a pilot"): a
// small image of the same view, rendered before the render with its own seed, that measures
// how well each of stage5's two strategies, the light sample and the BSDF sample, estimates
// the direct light at the scene's diffuse and at its glossy vertices under the render's own
// sampler (common/kernel/mis_pilot.glsl). The ratio of their errors sets the factor on the
// light pdf in the MIS weights (FrameParams::mis_diffuse, mis_glossy): the power heuristic
// with each strategy counted in inverse proportion to its variance, as variance-aware MIS
// (Grittmann et al. 2019) counts them. Any factor keeps the estimator unbiased (the two
// weights still sum to 1 at every direction); the pilot only chooses one that keeps its
// variance low.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include <glm/glm.hpp>

#include "common/render/backend.h"

namespace pt {

// The factors are powers of two within these bounds: a factor of 2^8 leaves the other
// strategy at most 2^-16 of its power-heuristic share, as good as none, and powers of two
// make the CPU's and the GPU's pilots, whose sums differ in their last bits, choose the same.
inline constexpr float kMisScaleMin = 1.0f / 256.0f;
inline constexpr float kMisScaleMax = 256.0f;

// The pilot's image: the view at most this many pixels on its longer side, and its samples
// per pixel in each of its two renders (one pass each).
inline constexpr int kMisPilotSide = 32;
inline constexpr std::uint64_t kMisPilotSpp = 16;

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
  int width = 0, height = 0;  // the pilot's image (0: no pilot ran)
};

// Runs the pilot on `backend` (set_scene done) with `params` (the render's: the pilot's
// image size, seed, samples and factors are set here), into `buffer` (at least the pilot's
// pixels); `glossy`: the scene has glossy lobes, else their class keeps the factor 1.
MisScales run_mis_pilot(Backend& backend, FrameParams params, bool glossy, std::span<glm::vec4> buffer);

// For the summary line: "[mis pilot: 32x32, light pdf x16 at diffuse, x1 at glossy vertices]".
std::string mis_summary(const MisScales& scales);

}  // namespace pt
