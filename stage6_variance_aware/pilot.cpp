// stage6_variance_aware's pilot, the host's side (see pilot.h): two small independent renders
// per lobe class in pilot mode, each strategy's error from their difference, the factor from
// the errors' ratio.
#include "stage6_variance_aware/pilot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "common/render/render.h"  // kMaxPassSamples

namespace stage6 {

float mis_scale_from(const MisPilotErrors& e) {
  if (!std::isfinite(e.light) || !std::isfinite(e.bsdf)) return 1.0f;
  if (!(e.light > 0.0) && !(e.bsdf > 0.0)) return 1.0f;  // no direct light seen
  if (!(e.light > 0.0)) return kMisScaleMax;
  if (!(e.bsdf > 0.0)) return kMisScaleMin;
  const double power = std::round(std::log2(e.bsdf / e.light));
  return float(std::clamp(std::exp2(power), double(kMisScaleMin), double(kMisScaleMax)));
}

static_assert(kMisPilotSpp <= pt::kMaxPassSamples, "the pilot is one pass");

MisScales measure_mis_scales(pt::Backend& backend, pt::FrameParams params, bool glossy, std::span<glm::vec4> buffer) {
  MisScales scales;
  const double shrink = std::min(1.0, double(kMisPilotSide) / double(std::max(params.width, params.height)));
  scales.width = std::max(1, int(std::lround(params.width * shrink)));
  scales.height = std::max(1, int(std::lround(params.height * shrink)));
  const std::size_t pixels = std::size_t(scales.width) * std::size_t(scales.height);
  std::span<glm::vec4> out = buffer.first(pixels);
  params.width = pt::uint(scales.width), params.height = pt::uint(scales.height), params.first_row = 0;
  params.stage_params = glm::vec4(0.0f);  // factors 1: what each strategy finds unweighted
  const std::uint32_t seed = params.seed;
  for (pt::uint lobe_class = 0; lobe_class < (glossy ? 2u : 1u); lobe_class++) {
    params.stage_params.x = float(1u + lobe_class);
    // Two independent renders of the pilot (their own seeds: the render's numbers do not
    // depend on them), each pixel's means of the two strategies' estimates in each.
    std::vector<glm::dvec2> mean[2];
    for (int replica = 0; replica < 2; replica++) {
      params.seed = seed ^ (replica == 0 ? 0x6d2b79f5u : 0x2545f491u);
      params.first_sample = 0, params.sample_count = kMisPilotSpp;  // one pass (render.h's longest)
      backend.run_pass(params, out);
      mean[replica].resize(pixels);
      for (std::size_t i = 0; i < pixels; i++) mean[replica][i] = glm::dvec2(out[i].x, out[i].y) / double(kMisPilotSpp);
    }
    // (first - second)^2 / 2 estimates the variance of one render's mean, whatever the
    // sampler: the two are independent (a pixel's halves would not do here: under the Sobol
    // points they overstate a smooth estimate's error far more than a rough one's).
    MisPilotErrors errors;
    for (std::size_t i = 0; i < pixels; i++) {
      const glm::dvec2 d = mean[0][i] - mean[1][i];
      errors.light += 0.5 * d.x * d.x, errors.bsdf += 0.5 * d.y * d.y;
    }
    (lobe_class == 0 ? scales.diffuse : scales.glossy) = mis_scale_from(errors);
  }
  return scales;
}

pt::StageTuning run_pilot(pt::Backend& backend, const pt::FrameParams& params, pt::uint features,
                          std::span<glm::vec4> buffer) {
  const bool glossy = (features & (pt::kFeatureConductor | pt::kFeatureMixed | pt::kFeatureDielectric | pt::kFeatureRoughGlass)) != 0u;
  const MisScales scales = measure_mis_scales(backend, params, glossy, buffer);
  pt::StageTuning tuning;
  tuning.params = glm::vec4(0.0f, std::log2(scales.diffuse), std::log2(scales.glossy), 0.0f);
  tuning.note = mis_summary(scales);
  return tuning;
}

std::string mis_summary(const MisScales& m) {
  auto factor = [](float k) {
    char text[32];
    std::snprintf(text, sizeof text, k >= 1.0f ? "x%.0f" : "x1/%.0f", k >= 1.0f ? double(k) : 1.0 / double(k));
    return std::string(text);
  };
  return "[mis pilot: " + std::to_string(m.width) + "x" + std::to_string(m.height) + ", light pdf " +
         factor(m.diffuse) + " at diffuse, " + factor(m.glossy) + " at glossy vertices]";
}

}  // namespace stage6
