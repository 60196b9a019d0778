// stage6_variance_aware's pilot (beyond the article; pilot.h, mis_pilot.glsl): the light pdf's
// factor in the MIS weights from two small renders measuring each strategy's error. Its rule,
// its factors where the answer is known, what render() does with them, the pilot pass's
// closed form, and that any factor, forced, keeps the image unbiased.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "common/render/render.h"
#include "common/scene/analytic_scenes.h"
#include "common/scene/scene.h"
#include "common/scene/scene_loading.h"
#include "stage5_mis/kernels.h"
#include "stage6_variance_aware/kernels.h"
#include "stage6_variance_aware/pilot.h"
#include "tests/support/analytic_suite.h"
#include "tests/support/image_checks.h"
#include "tests/support/statistics.h"
#include "tests/support/test_render.h"

using namespace pt;
using namespace pt::test;

namespace {

// The pilot's findings for a scene: stage6's hook run on the backend under test as
// render() runs it (after set_scene, with the render's params and feature bits).
struct Pilot {
  float diffuse = 1.0f, glossy = 1.0f;  // the light pdf's factors (2^stage_params.y, .z)
  StageTuning tuning;
};

Pilot run_pilot_on(const Scene& scene, const RenderSettings& s) {
  std::unique_ptr<Backend> backend = make_backend(backend_under_test, stage6::kernels());
  const uint features = scene_feature_mask(scene, s.sky);
  backend->set_scene(scene, features, nullptr);
  std::vector<glm::vec4> buffer(std::size_t(stage6::kMisPilotSide) * stage6::kMisPilotSide);
  Pilot p;
  p.tuning = stage6::run_pilot(*backend, make_frame_params(scene, s), features, buffer);
  p.diffuse = std::exp2(p.tuning.params.y);
  p.glossy = std::exp2(p.tuning.params.z);
  return p;
}

// A before-render hook that hands the kernel chosen factors instead of the pilot's.
glm::vec4 forced_params(0.0f);
StageTuning forced_factors(Backend&, const FrameParams&, uint, std::span<glm::vec4>) {
  return StageTuning{forced_params, "[forced factors]"};
}

}  // namespace

TEST_CASE("stage6 pilot: the factor is the ratio of the BSDF strategy's error to the light strategy's, a power of two",
          "[stage6]") {
  using stage6::mis_scale_from;
  CHECK(mis_scale_from({1.0, 1.0}) == 1.0f);
  CHECK(mis_scale_from({1.0, 16.0}) == 16.0f);
  CHECK(mis_scale_from({1.0, 22.0}) == 16.0f);  // log2 22 = 4.46
  CHECK(mis_scale_from({1.0, 23.0}) == 32.0f);  // 4.52
  CHECK(mis_scale_from({8.0, 1.0}) == 0.125f);
  // Within the bounds.
  CHECK(mis_scale_from({1.0, 1e9}) == stage6::kMisScaleMax);
  CHECK(mis_scale_from({1e9, 1.0}) == stage6::kMisScaleMin);
  CHECK(stage6::kMisScaleMax == 256.0f);
  CHECK(stage6::kMisScaleMin == 1.0f / 256.0f);
  // One strategy exact: the other gets as good as no weight; no direct light: the heuristic.
  CHECK(mis_scale_from({0.0, 3.0}) == stage6::kMisScaleMax);
  CHECK(mis_scale_from({3.0, 0.0}) == stage6::kMisScaleMin);
  CHECK(mis_scale_from({0.0, 0.0}) == 1.0f);
  CHECK(mis_scale_from({std::nan(""), 1.0}) == 1.0f);
  CHECK(mis_scale_from({1.0, INFINITY}) == 1.0f);
  CHECK(stage6::mis_summary(stage6::MisScales{16.0f, 0.25f, 32, 24}) ==
        "[mis pilot: 32x24, light pdf x16 at diffuse, x1/4 at glossy vertices]");
}

TEST_CASE("stage6 pilot: the light strategy counts more under a square light, the BSDF strategy in the box furnace",
          "[stage6][statistical]") {
  auto pilot = [](const std::string& name, int width, int height, std::uint32_t seed) {
    Pilot p = run_pilot_on(make_builtin_scene(name), settings(width, height, 1, seed));
    INFO(name << ": " << p.tuning.note);
    CHECK(p.tuning.params.x == 0.0f);  // the render that follows is no pilot pass
    CHECK(p.glossy == 1.0f);           // no glossy lobes: not measured
    CHECK(p.tuning.note.find("[mis pilot: 32x32, ") == 0);
    return p.diffuse;
  };
  // The light sample drawn by solid angle is a smooth function of its numbers there; the
  // BSDF sample finds the light or misses it (measured at d54ac1b: errors 14 and 8500 times apart).
  CHECK(pilot("floor_large_light", 64, 64, test_seed(6400)) >= 4.0f);
  CHECK(pilot("floor_small_light", 64, 64, test_seed(6410)) >= 64.0f);
  // Every BSDF sample finds emission; the light sample picks one of 12 wall triangles by
  // area, whatever its solid angle (measured: 5 times apart).
  CHECK(pilot("furnace", 64, 64, test_seed(6420)) <= 0.5f);
  // The Cornell box: a small light overhead (measured: 86 times apart).
  CHECK(pilot("cornell", 64, 64, test_seed(6430)) >= 4.0f);
  // Glossy lobes (GGX, roughness 0.3) are measured apart: neither strategy is clearly
  // better there, and their factor, a ratio of two heavy-tailed error estimates, spreads
  // (x1/4 to x8 over 20 seeds), far from the diffuse vertices' (x32 to x256).
  Pilot glossy = run_pilot_on(make_builtin_scene("cornell_glossy"), settings(48, 48, 1, test_seed(6440)));
  INFO(glossy.tuning.note);
  CHECK(glossy.tuning.note.find("[mis pilot: 32x32, ") == 0);
  CHECK(glossy.diffuse >= 4.0f);
  CHECK(glossy.glossy >= 1.0f / 16.0f);
  CHECK(glossy.glossy <= 16.0f);
  CHECK(glossy.glossy < glossy.diffuse);
}

TEST_CASE("stage6 pilot: render() hands the pilot's factors to the kernel and its note to the summary; stage5 has none",
          "[stage6]") {
  Scene scene = make_builtin_scene("floor_small_light");
  RenderSettings s = settings(40, 20, 2, test_seed(6450));
  Pilot p = run_pilot_on(scene, s);
  RenderResult r = render_on_test_backend(stage6::kernels(), scene, s);
  CHECK(r.stage_note == p.tuning.note);
  CHECK(r.stage_note.find("[mis pilot: 32x16, light pdf x") == 0);
  CHECK(r.stage_note.find("at diffuse, x1 at glossy vertices]") != std::string::npos);
  // The pilot is deterministic: a resumed render or a part runs it again and must agree.
  CHECK(run_pilot_on(scene, s).tuning.params == p.tuning.params);
  // Stages without a step before the render have none, and render() then leaves the note empty.
  CHECK(stage5::kernels().before_render == nullptr);
  StageKernels no_hook = stage6::kernels();
  no_hook.before_render = nullptr;
  CHECK(render_on_test_backend(no_hook, scene, settings(8, 8, 1, 1)).stage_note.empty());
  CHECK(stage6::kernels().before_render != nullptr);
}

TEST_CASE("stage6 pilot: a render split at a pass end adds the samples of one run, bit for bit", "[stage6]") {
  Scene scene = make_builtin_scene("floor_large_light");
  RenderSettings all = settings(24, 16, 48, 77);
  RenderResult one = render_on_test_backend(stage6::kernels(), scene, all);
  RenderSettings first = all, second = all;
  first.spp = 32;
  second.first_sample = 32, second.spp = 16;
  RenderResult a = render_on_test_backend(stage6::kernels(), scene, first);
  RenderResult b = render_on_test_backend(stage6::kernels(), scene, second);
  // Each part ran the same pilot (the samples asked for are not among its inputs).
  CHECK(a.stage_note == one.stage_note);
  CHECK(b.stage_note == one.stage_note);
  CHECK(one.stage_note.find("light pdf x1 at") == std::string::npos);  // the factor is in play here
  Film merged = a.film;
  merged.merge(b.film, true);
  REQUIRE(merged.spp() == one.film.spp());
  CHECK(merged.sums() == one.film.sums());
}

TEST_CASE("stage6: whatever the light pdf's factor (1/256 to 256, forced), the floor under a square light matches "
          "Lambert's formula: the two weights still sum to 1",
          "[stage6][statistical][analytic]") {
  // Variance-aware weights are the power heuristic with the light pdf scaled by k: a light
  // sample weighs (k p_l)^2 / ((k p_l)^2 + p_b^2), a BSDF sample p_b^2 / ((k p_l)^2 + p_b^2),
  // and the two sum to 1 for every direction, so the estimate stays unbiased for any k.
  // A factor applied to one of the weights only would not: at k = 16 the light sample's
  // weight rises from about 0.95 to 1 on the floor under the light and the image by about
  // 5%; at k = 1/16 it falls to about 0.06. The default light (half-size 0.5 at height 1)
  // keeps the BSDF strategy's variance finite and well measured at every factor.
  analytic::FloorLightScene a;
  const int size = 16;
  StageKernels forced = stage6::kernels();
  forced.before_render = &forced_factors;
  std::uint32_t seed = test_seed(6460);
  for (float log2_factor : {-8.0f, -4.0f, 4.0f, 8.0f}) {
    forced_params = glm::vec4(0.0f, log2_factor, log2_factor, 0.0f);
    INFO("light pdf x2^" << log2_factor);
    check_scene(forced, analytic::make_floor_light(a), floor_light_image(a, size), settings(size, size, 256, seed));
    seed += 10;
  }
  forced_params = glm::vec4(0.0f);
}

TEST_CASE("stage6 pilot: in a pilot pass the light sample alone and the BSDF sample alone each find the floor's "
          "direct light of Lambert's formula",
          "[stage6][statistical][analytic]") {
  // On the floor under the square light the one vertex with direct light is the floor point
  // the camera sees (the emitter's black side reflects nothing), at path weight 1. The pilot
  // sums each strategy's unweighted estimate there (stage_params.x = 1: the diffuse class),
  // X_l in the pass's first channel and X_b in its second: each is then an unbiased estimate
  // of the direct light, Lambert's image. An X weighted by its MIS weight would fall short
  // of it (by about 5% for X_l, 95% for X_b at the image's centre). Tested on the image mean
  // over 32 independent passes (seeds), t-tests Sidak-corrected over the two strategies.
  analytic::FloorLightScene a;
  const int size = 32, passes = 32;
  const Scene scene = analytic::make_floor_light(a);
  double want = 0.0;
  for (const glm::dvec3& v : floor_light_image(a, size)) want += luminance(v) / (size * size);
  std::unique_ptr<Backend> backend = make_backend(backend_under_test, stage6::kernels());
  backend->set_scene(scene, scene_feature_mask(scene, glm::vec3(0.0f)), nullptr);
  FrameParams p = make_frame_params(scene, settings(size, size, 1, 0));
  p.stage_params = glm::vec4(1.0f, 0.0f, 0.0f, 0.0f);
  p.first_sample = 0, p.sample_count = stage6::kMisPilotSpp;
  std::vector<glm::vec4> out(std::size_t(size) * size);
  glm::dvec2 sum(0.0), sum2(0.0);  // over the passes: the image means of X_l and X_b, and their squares
  for (int k = 0; k < passes; k++) {
    p.seed = test_seed(6470) + std::uint32_t(k);
    backend->run_pass(p, out);
    glm::dvec2 mean(0.0);
    for (const glm::vec4& v : out) mean += glm::dvec2(v.x, v.y) / double(out.size() * stage6::kMisPilotSpp);
    sum += mean, sum2 += mean * mean;
  }
  const glm::dvec2 mean = sum / double(passes);
  const glm::dvec2 se = glm::sqrt((sum2 / double(passes) - mean * mean) / double(passes - 1));
  const double t = student_two_sided_quantile(sidak_alpha(1e-3, 2.0), passes - 1);
  INFO("want " << want << "; X_l " << mean.x << " +- " << se.x << ", X_b " << mean.y << " +- " << se.y << " (t " << t << ")");
  CHECK(std::abs(mean.x - want) <= t * se.x);
  CHECK(std::abs(mean.y - want) <= t * se.y);
  CHECK(t * se.x < 0.05 * want);  // the test resolves a 5% shortfall
  CHECK(t * se.y < 0.05 * want);
}
