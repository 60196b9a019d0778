// The user's trade of time for accuracy (render.h): --target-error stops when the
// estimated relative standard error of the image mean is reached, and that estimate is
// honest against the closed form; --time-budget stops after the pass that spends it.
#include <catch2/catch.hpp>

#include <cmath>

#include "common/scene/analytic_scenes.h"
#include "stage3_importance/kernels.h"
#include "tests/support/test_render.h"

using namespace pt;
using namespace pt::test;

TEST_CASE("trade: the estimated error is honest and --target-error 0.01 ends below about 0.015 measured",
          "[trade][statistical]") {
  analytic::FurnaceScene furnace;
  furnace.albedo = 0.8f;  // answer 5
  Scene scene = analytic::make_furnace(furnace);
  RenderSettings s = settings(4, 4, 0xffffffffu, test_seed(3000));
  s.roulette = kRouletteThroughput;
  s.target_error = 0.01;
  int below = 0, honest = 0;
  const int runs = 20;
  for (int i = 0; i < runs; i++, s.seed++) {
    RenderResult r = render_on_test_backend(stage3::kernels(), scene, s);
    double estimated = r.film.relative_standard_error();
    double measured = std::abs(r.film.mean_luminance() - 5.0) / 5.0;
    CHECK(estimated <= 0.01);
    below += measured < 0.015;
    // A standard error says where the error usually is: within a factor 2 of it, or
    // below it (an error much smaller than its standard error is luck, not dishonesty).
    honest += measured <= 2.0 * estimated;
  }
  // The measured error is |N(0, e)|: below 1.5 e in 87% of runs, below 2 e in 95%.
  // Binomial(20, 0.87) is >= 13 with probability 0.998; Binomial(20, 0.95) >= 16 with 0.984.
  CHECK(below >= 13);
  CHECK(honest >= 16);
}

TEST_CASE("trade: --time-budget stops after the pass that spends it, with a correct image of its spp", "[trade]") {
  Scene scene = analytic::make_furnace({});
  RenderSettings s = settings(32, 32, 0xffffffffu, 1);
  s.roulette = kRouletteThroughput;
  s.time_budget = 0.2;
  RenderResult r = render_on_test_backend(stage3::kernels(), scene, s);
  CHECK(r.seconds >= 0.2);
  CHECK(r.film.spp() > 0);
  CHECK(r.film.spp() < 0xffffffffu);
}
