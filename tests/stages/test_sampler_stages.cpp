// The sampler under the stages (common/kernel/sampler.glsl, issue "Samples that cover the
// domain"): on a smooth integrand with a closed form, stage4's light-sampled floor under a
// square light (builtin:floor_light, Lambert's polygon formula pixel by pixel), the error of
// Owen-scrambled Sobol samples falls faster than N^-1/2, while independent samples fall as
// N^-1/2 (the control that shows the test can tell them apart). And the per-pixel error the
// renderer prints stays honest under the sampler: the pixel's sample variance over N does
// not understate the error measured against the closed form.
#include <catch2/catch.hpp>

#include <cmath>
#include <sstream>
#include <vector>

#include "common/scene/analytic_scenes.h"
#include "stage4_direct_indirect/kernels.h"
#include "tests/support/analytic_suite.h"
#include "tests/support/statistics.h"
#include "tests/support/test_render.h"

using namespace pt;
using namespace pt::test;

namespace test_sampler_stages {  // this file's names: the unity build compiles it with others (tests/CMakeLists.txt)

namespace {

constexpr int kSize = 16;

struct Errors {
  double rmse = 0.0;       // RMS over pixels of the luminance error against the closed form
  double estimated = 0.0;  // RMS over pixels of the renderer's own estimate, sqrt(variance / N)
};

Errors measure(std::uint32_t sampler, std::uint64_t spp, std::uint32_t seed) {
  analytic::FloorLightScene a;
  ExpectedImage expected = floor_light_image(a, kSize);
  RenderSettings s = settings(kSize, kSize, spp, seed);
  s.sampler = sampler;
  Film film = render_on_test_backend(stage4::kernels(), analytic::make_floor_light(a), s).film;
  Errors e;
  for (int y = 0; y < kSize; y++) {
    for (int x = 0; x < kSize; x++) {
      double d = luminance(film.mean(x, y)) - luminance(expected[std::size_t(y) * kSize + x]);
      e.rmse += d * d;
      e.estimated += film.sample_variance(x, y) / double(spp);
    }
  }
  e.rmse = std::sqrt(e.rmse / (kSize * kSize));
  e.estimated = std::sqrt(e.estimated / (kSize * kSize));
  return e;
}


}  // namespace

TEST_CASE("sampler: stage4's error on the floor under a square light falls as N^-1.2 with sobol (measured -1.19, 20 seeds -1.12..-1.25), N^-0.5 independent",
          "[stage4][sampler][statistical]") {
  // RMSE over 256 pixels (each its own randomisation): relative standard error about 4%,
  // so a slope fitted over 16..1024 spp is good to about +-0.04 (20 seeds: sobol -1.12 to
  // -1.25, independent -0.46 to -0.53). At 1024 spp sobol's RMSE is about 1/100 of
  // independent samples'. The pixel position and the light's pick and point share the
  // sampler's block 0 (sampler.glsl): with the light in a block of its own the slope was
  // -0.6, the pixel's and the light's numbers stratified each alone but not together.
  std::vector<double> ns, sobol, independent;
  std::uint32_t seed = test_seed(8400);
  for (std::uint64_t spp : {16u, 64u, 256u, 1024u}) {
    ns.push_back(double(spp));
    sobol.push_back(measure(kSamplerSobol, spp, seed++).rmse);
    independent.push_back(measure(kSamplerIndependent, spp, seed++).rmse);
  }
  double qmc = pt::test::log_slope(ns, sobol), mc = pt::test::log_slope(ns, independent);
  std::ostringstream table;
  for (std::size_t i = 0; i < ns.size(); i++) table << "\n  " << ns[i] << " spp: sobol " << sobol[i] << ", independent " << independent[i];
  INFO("slopes of log RMSE over log N: sobol " << qmc << ", independent " << mc << "; RMSE:" << table.str());
  CHECK(qmc < -0.9);
  CHECK(qmc > -1.5);
  CHECK(mc > -0.6);
  CHECK(mc < -0.4);
}

TEST_CASE("sampler: under sobol the printed per-pixel error does not understate the measured error",
          "[stage4][sampler][statistical]") {
  // The pixel's sample variance over N estimates the error of independent samples; under
  // randomised QMC it is an upper bound whenever the sampler does better than independent
  // numbers (docs/sampling.md). Measured against the closed form at 64 and 256 spp.
  std::uint32_t seed = test_seed(8500);
  for (std::uint64_t spp : {64u, 256u}) {
    Errors e = measure(kSamplerSobol, spp, seed++);
    INFO(spp << " spp: measured RMSE " << e.rmse << ", estimated " << e.estimated);
    CHECK(e.rmse <= e.estimated);
  }
}

}  // namespace test_sampler_stages
