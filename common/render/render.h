// The render loop shared by every stage: passes of doubling sample counts on a backend,
// added up by the film, with a progress line on a terminal. The pass schedule depends only
// on the sample count, so the same seed and options give the same image on a backend.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "common/render/backend.h"
#include "common/render/film.h"
#include "common/scene/bvh.h"

namespace pt {

struct Scene;

// What a render computes and when it stops: the options of the contract that change the
// image or end the render (common/app/options.h holds one).
struct RenderSettings {
  int width = 512;
  int height = 512;
  std::uint64_t spp = 1;           // how many samples of each pixel this render adds
  std::uint64_t first_sample = 0;  // the index of the first (--samples FIRST:COUNT; --spp N is 0:N)
  std::uint32_t seed = 0;
  glm::vec3 sky{0.0f};
  std::uint32_t roulette = kRouletteFixed;  // stage2 onwards
  std::uint32_t depth_cap = 1000;           // stage2 onwards: a safety net only
  double time_budget = 0.0;                 // seconds; > 0: stop after the pass that spends it
  double target_error = 0.0;                // > 0: stop once the estimated per-pixel relative
                                            // error (Film::per_pixel_relative_error) is below it
  bool all_features = false;                // the general kernel, not the one specialised
                                            // to the scene's features (--all-features)
  std::uint32_t accel = kAccelBvh;          // kAccelBvh or kAccelNone (--accel): how the
                                            // triangles are searched; the same image
  std::uint32_t sampler = kSamplerSobol;    // kSamplerSobol or kSamplerIndependent (--sampler):
                                            // where the random numbers come from
};

// How a render is watched and resumed; none of it changes the image.
struct RenderHooks {
  bool progress = false;         // progress line on stderr (on a terminal)
  const char* label = "render";  // names the progress line
  // Checkpoints (common/app/checkpoint.h): continue from this state instead of an empty film,
  // and hand the state to `save` every save_seconds, at an interrupt and at a device
  // failure (never after a pass cut short by --spp: the schedule must stay whole).
  const struct RenderResult* resume = nullptr;
  std::function<void(const struct RenderResult&)> save;
  double save_seconds = 0.0;
  // A BVH already built over the scene's triangles (build_bvh): used instead of building
  // one, so that a render continued on another backend, or rendered again, builds it once.
  const Bvh* bvh = nullptr;
};

// The kernels' event counters, summed over the passes (scene_types.h, kCounter*).
struct RenderCounters {
  std::uint64_t depth_cap = 0;   // paths stopped by the depth cap
  std::uint64_t zero_pdf = 0;    // paths ended by a zero pdf or a non-finite weight
  std::uint64_t non_finite = 0;  // NaN or infinite samples dropped
  std::uint32_t first_non_finite_pixel = kNoPixel;
  void add(const PassResult& pass);
};

struct RenderResult {
  Film film;
  double seconds = 0.0;         // wall time of the passes
  double kernel_seconds = 0.0;  // time the kernels ran (GPU: timestamp queries)
  RenderCounters counters;
  std::uint64_t passes = 0;  // passes done (the schedule follows from the samples done)
  std::string device_error;  // set when the backend failed (exit 4), or when the Vulkan
                             // driver cut a pass short (a wrong pass is never added): the
                             // film has the samples done before it
  std::optional<BvhStats> bvh;  // the BVH this render searched (none: --accel none or no triangles)
  std::string stage_note;       // what the stage's step before the render found (StageTuning)
};

// Largest number of samples per pixel in one pass: passes stay short (a desktop GPU's
// watchdog) and the progress line moves.
constexpr std::uint64_t kMaxPassSamples = 16;

// Largest sample index + 1 a render can address (FrameParams.first_sample is 32 bits).
constexpr std::uint64_t kSampleIndexLimit = std::uint64_t(1) << 32;

// --target-error trusts the variance estimate only after this many samples per pixel.
constexpr std::uint64_t kMinSamplesForError = 16;

// The pass schedule, one for every render: passes end at the sample indices 1, 2, 4, 8, 16
// and every multiple of kMaxPassSamples after that (passes of 1, 1, 2, 4, 8, 16, 16, ...
// samples). A render of the samples FIRST ... FIRST + COUNT - 1 runs the parts of these
// passes that fall in its range, so parts split at pass ends add the same passes as one
// run, and their merge is that run bit for bit. Returns where the pass holding `sample` ends.
std::uint64_t pass_end(std::uint64_t sample);
bool is_pass_end(std::uint64_t sample);  // 0 too: the start of the first pass

// The parameters every pass shares (the first sample index and count are set per pass).
FrameParams make_frame_params(const Scene& scene, const RenderSettings& settings);

RenderResult render(Backend& backend, const Scene& scene, const RenderSettings& settings,
                    const RenderHooks& hooks = {});

}  // namespace pt
