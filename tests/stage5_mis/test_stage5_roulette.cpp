// stage5_mis's Russian roulette through glass (beyond the article; issue #18): the roulette
// reads the path weight without the radiance scale 1 / eta^2 that entering glass puts into
// it and leaving undoes (pbrt-v4's etaScale), so it does not end most paths inside glass.
// Without that, a path inside a glass of ior 1.5 survives with probability 1 / 2.25: in
// smallpt's scene that doubled stage5's error under the glass ball (docs/results.md).
#include <catch2/catch.hpp>

#include <cmath>

#include "common/scene/analytic_scenes.h"
#include "stage5_mis/kernels.h"
#include "tests/support/test_render.h"

using namespace pt;
using namespace pt::test;

TEST_CASE("stage5: through a glass slab every sample is Le or 0 (variance Le^2 p (1 - p)): the roulette ends no path inside the glass",
          "[stage5][statistical][analytic]") {
  // Normal incidence through the slab onto an emitter of Le = 1 (white, luminance 1), black
  // behind the camera: each path leaves the glass towards the emitter (Le, its weights
  // 1 / eta^2 and eta^2 cancelling, reflections weighing F / F = 1) or back towards the
  // camera (0). So a sample is a Bernoulli variable with p = (1 - R) / (1 + R), the slab's
  // transmittance, R = ((ior - 1) / (ior + 1))^2, and variance p (1 - p) = 0.071 at ior 1.5,
  // as long as the roulette (p = the path weight) never plays: with the weight 1 / 2.25
  // inside the glass read as it is, a transmitted sample would be 2.25 Le with probability
  // 1 / 2.25, and the variance 2.25 p - p^2 = 1.23, 17 times as much.
  analytic::GlassSlabScene a;
  const double R = std::pow((a.ior - 1.0) / (a.ior + 1.0), 2.0), p = (1.0 - R) / (1.0 + R);
  const double variance = p * (1.0 - p);
  const int size = 12;
  RenderSettings s = settings(size, size, 256, test_seed(5900));
  s.roulette = kRouletteThroughput;
  s.sampler = kSamplerIndependent;  // the film's sample variance is then the estimator's
  RenderResult r = render_on_test_backend(stage5::kernels(), analytic::make_glass_slab(a), s);
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
