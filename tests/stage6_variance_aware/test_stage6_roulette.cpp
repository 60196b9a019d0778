// stage6_variance_aware's Russian roulette through glass (beyond the article; issue #18,
// #48): the roulette reads the path weight without the radiance scale 1 / eta^2 that entering
// glass puts into it and leaving undoes (eta_scale, pbrt-v4's etaScale), so it ends no path
// inside glass; and eta_scale is the roulette's alone: the path weight keeps the scale.
#include <catch2/catch.hpp>

#include <cmath>

#include "common/scene/analytic_scenes.h"
#include "stage6_variance_aware/kernels.h"
#include "tests/support/analytic_suite.h"
#include "tests/support/test_render.h"

using namespace pt;
using namespace pt::test;

TEST_CASE("stage6: through a glass slab every sample is Le or 0 (variance Le^2 p (1 - p)): the roulette ends no path inside the glass",
          "[stage6][statistical][analytic]") {
  // Normal incidence through the slab onto an emitter of Le = 1 (white, luminance 1), black
  // behind the camera: each path leaves the glass towards the emitter (Le, its weights
  // 1 / eta^2 and eta^2 cancelling, reflections weighing F / F = 1) or back towards the
  // camera (0). So a sample is a Bernoulli variable with p = (1 - R) / (1 + R), the slab's
  // transmittance, R = ((ior - 1) / (ior + 1))^2, and variance p (1 - p) = 0.071 at ior 1.5,
  // as long as the roulette never plays: were the weight 1 / 2.25 inside the glass read as
  // it is (no eta_scale), the square-root roulette would go on with p = sqrt(1 / 2.25) there,
  // and a transmitted sample be 1.5 Le with probability 2 / 3: variance 1.5 p - p^2 = 0.53,
  // 7.5 times as much.
  analytic::GlassSlabScene a;
  const double R = std::pow((a.ior - 1.0) / (a.ior + 1.0), 2.0), p = (1.0 - R) / (1.0 + R);
  const double variance = p * (1.0 - p);
  const int size = 12;
  RenderSettings s = settings(size, size, 256, test_seed(6900));
  s.roulette = kRouletteThroughput;
  s.sampler = kSamplerIndependent;  // the film's sample variance is then the estimator's
  RenderResult r = render_on_test_backend(stage6::kernels(), analytic::make_glass_slab(a), s);
  double mean = 0.0, measured = 0.0;
  for (int y = 0; y < size; y++) {
    for (int x = 0; x < size; x++) {
      mean += luminance(r.film.mean(x, y));
      measured += r.film.sample_variance(x, y);
    }
  }
  const double pixels = size * size, n = double(s.spp) * pixels;
  mean /= pixels;
  measured /= pixels;
  // The standard error of the pixels' unbiased sample variances, averaged: for a Bernoulli
  // variable the kurtosis is (1 - 3pq) / pq, and Var(s^2) ~ sigma^4 (kurtosis - 1) / n per
  // pixel; over all the pixels' samples 1.7% of the variance.
  const double kurtosis = (1.0 - 3.0 * variance) / variance;
  const double variance_error = variance * std::sqrt((kurtosis - 1.0) / n);
  INFO("transmittance " << p << ": mean " << mean << "; variance per sample " << measured << ", want " << variance
                        << " +- " << variance_error);
  CHECK(std::abs(mean - p) < 5.0 * std::sqrt(variance / n));
  CHECK(std::abs(measured - variance) < 5.0 * variance_error);
}

TEST_CASE("stage6: a glass slab of ior 1 is invisible; of ior 1.5 it transmits (1 - R) / (1 + R)",
          "[stage6][statistical][analytic]") {
  check_glass_slab(stage6::kernels(), 1.0f, test_seed(6600));
  check_glass_slab(stage6::kernels(), 1.5f, test_seed(6610));
}

TEST_CASE("stage6: seen from inside a glass slab the emitter behind it is eta^2 Le / (1 + R): the path weight keeps "
          "the radiance scale that eta_scale takes out for the roulette only",
          "[stage6][statistical][analytic]") {
  // The camera at the slab's centre, inside the glass, looking at the emitter through the
  // slab's far side. A path leaves the glass towards the emitter with probability (1 - R)
  // (1 + R^2 + R^4 + ...) = 1 / (1 + R), the rest leaving on the near side into black, and
  // leaving glass scales radiance by eta^2 (radiance / n^2 is what is conserved): the pixel
  // is 2.25 Le / (1 + R) = 2.163 at ior 1.5. Were eta_scale multiplied into the path weight
  // as well, its eta^2 and leaving's 1 / eta^2 would cancel: Le / (1 + R) = 0.961.
  for (std::uint32_t roulette : {kRouletteThroughput, kRouletteFixed}) {
    analytic::GlassSlabScene a;
    a.camera_z = 0.0f;
    const double R = std::pow((a.ior - 1.0) / (a.ior + 1.0), 2.0);
    const double want = a.ior * a.ior * a.emission / (1.0 + R);
    RenderSettings s = settings(12, 12, 256, test_seed(roulette == kRouletteFixed ? 6620 : 6630));
    s.roulette = roulette;
    INFO((roulette == kRouletteFixed ? "--rr fixed" : "--rr throughput") << ": want " << want);
    check_scene(stage6::kernels(), analytic::make_glass_slab(a), ExpectedImage(12 * 12, glm::dvec3(want)), s);
  }
}
