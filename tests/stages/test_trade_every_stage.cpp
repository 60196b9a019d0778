// The user's trade of time for accuracy (issue: the speed-versus-accuracy lab) on every
// stage of the article (Eq. 2 to 5) and, since this file is one of the image tests, on both
// backends: --target-error stops once the estimated per-pixel relative error is below the
// target, --time-budget stops after the pass that spends the budget, and
// either way the image is a correct image of the samples it has. The estimate's honesty is
// tested in test_trade.cpp and test_convergence.cpp.
#include <catch2/catch.hpp>

#include <cmath>

#include "common/scene/analytic_scenes.h"
#include "stage1_raycast/kernels.h"
#include "stage2_montecarlo/kernels.h"
#include "stage3_importance/kernels.h"
#include "stage4_direct_indirect/kernels.h"
#include "tests/support/test_render.h"

using namespace pt;
using namespace pt::test;

namespace {

struct StageCase {
  const char* name;
  StageKernels (*kernels)();
  double answer;  // the furnace's value on this stage (albedo 0.5, emission 1)
};

// stage1 shows the emission only (Eq. 2): 1. The path tracers: Le / (1 - albedo) = 2.
const StageCase kStages[] = {{"stage1", stage1::kernels, 1.0},
                             {"stage2", stage2::kernels, 2.0},
                             {"stage3", stage3::kernels, 2.0},
                             {"stage4", stage4::kernels, 2.0}};

// The spherical furnace (albedo 0.5): no edges, so every stage's variance is finite and
// the estimated error can be trusted (in the box, light sampling's is not: results.md).
Scene half_furnace() { return analytic::make_furnace_sphere({}); }

}  // namespace

TEST_CASE("trade: --target-error and --time-budget stop every stage, with a correct image of its spp",
          "[trade]") {
  Scene scene = half_furnace();
  for (const StageCase& stage : kStages) {
    INFO(stage.name);
    RenderSettings s = settings(8, 8, 0xffffffffu, test_seed(4100));
    s.roulette = kRouletteThroughput;
    s.target_error = 0.05;
    RenderResult r = render_on_test_backend(stage.kernels(), scene, s);
    CHECK(r.film.per_pixel_relative_error() <= 0.05);
    CHECK(r.film.spp() >= kMinSamplesForError);
    CHECK(r.film.spp() < 0xffffffffu);
    // The image mean's error is at most the per-pixel one over sqrt(64 pixels): 5 of those
    // standard errors are a wrong image, not noise (the estimate is honest).
    CHECK(std::abs(r.film.mean_luminance() - stage.answer) <= 5.0 * 0.05 / 8.0 * stage.answer + 1e-6);

    RenderSettings t = settings(8, 8, 0xffffffffu, test_seed(4200));
    t.roulette = kRouletteThroughput;
    t.time_budget = 0.05;
    RenderResult b = render_on_test_backend(stage.kernels(), scene, t);
    CHECK(b.seconds >= 0.05);
    CHECK(b.film.spp() > 0);
    CHECK(b.film.spp() < 0xffffffffu);
  }
}
