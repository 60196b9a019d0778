// The error study's two laws, checked where the answer is known (issue 6, "Tests"): in the
// spherical furnace (every pixel Le / (1 - albedo) = 2, common/scene/analytic_scenes.h) the error the
// renderer estimates from its per-pixel variance matches the error measured against the
// closed form within a factor of 2 at every checkpoint, and the RMSE of every Monte Carlo
// stage halves as the samples quadruple (the 1/sqrt(N) law behind the bench's slope -1/2).
// The sphere, not the box: in the box, stage4's light sampling divides by the squared
// distance to the wall a point meets at an edge, a variance without bound (heavy tails:
// the MSE of one render does not settle), which docs/results.md shows on builtin:furnace.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "common/scene/analytic_scenes.h"
#include "stage2_montecarlo/kernels.h"
#include "stage3_importance/kernels.h"
#include "stage4_direct_indirect/kernels.h"
#include "tests/support/statistics.h"
#include "tests/support/test_render.h"

using namespace pt;
using namespace pt::test;

namespace test_convergence {  // this file's names: the unity build compiles it with others (tests/CMakeLists.txt)

namespace {

constexpr double kAnswer = 2.0;  // the furnace's every pixel, every channel
constexpr int kSize = 16;

struct Measured {
  double mse = 0.0;        // mean over pixels of the squared luminance error
  double mse_se = 0.0;     // its standard error, from the spread of the squared errors
  double est_mse = 0.0;    // the renderer's own estimate: mean over pixels of variance / spp
};

Measured measure(const StageKernels& kernels, std::uint64_t spp, std::uint32_t seed) {
  RenderResult r = render_on_test_backend(kernels, analytic::make_furnace_sphere({}), settings(kSize, kSize, spp, seed));
  std::vector<double> sq;
  Measured m;
  for (int y = 0; y < kSize; y++) {
    for (int x = 0; x < kSize; x++) {
      double e = pt::luminance(r.film.mean(x, y)) - kAnswer;
      sq.push_back(e * e);
      m.est_mse += r.film.sample_variance(x, y) / double(spp);
    }
  }
  double n = double(sq.size()), var = 0.0;
  for (double v : sq) m.mse += v / n;
  for (double v : sq) var += (v - m.mse) * (v - m.mse) / (n - 1.0);
  m.mse_se = std::sqrt(var / n);
  m.est_mse /= n;
  return m;
}

struct Stage {
  const char* name;
  StageKernels kernels;
};

std::vector<Stage> stages() {
  return {{"stage2", stage2::kernels()}, {"stage3", stage3::kernels()}, {"stage4", stage4::kernels()}};
}

}  // namespace

TEST_CASE("convergence: the estimated error matches the measured error within a factor 2 at every checkpoint",
          "[convergence][statistical]") {
  std::uint32_t seed = test_seed(7000);
  for (const Stage& stage : stages()) {
    for (std::uint64_t spp : {16u, 64u, 256u}) {
      Measured m = measure(stage.kernels, spp, seed++);
      double ratio = std::sqrt(m.mse / m.est_mse);  // measured RMSE / estimated RMSE
      INFO(stage.name << " at " << spp << " spp: measured RMSE " << std::sqrt(m.mse) << ", estimated "
                      << std::sqrt(m.est_mse));
      CHECK(ratio > 0.5);
      CHECK(ratio < 2.0);
    }
  }
}

TEST_CASE("convergence: the RMSE halves as the samples quadruple for every stage in the furnace",
          "[convergence][statistical]") {
  // 4 MSE(4N) / MSE(N) = 1 for an unbiased estimator. Independent seeds per checkpoint;
  // the tolerance is z standard errors of that ratio (delta method), z Sidak-corrected
  // for the 3 stages x 2 pairs at an overall false-alarm rate of 1e-3.
  const double z = normal_two_sided_quantile(sidak_alpha(1e-3, 6.0));
  std::uint32_t seed = test_seed(7100);
  for (const Stage& stage : stages()) {
    Measured prev = measure(stage.kernels, 16, seed++);
    for (std::uint64_t spp : {64u, 256u}) {
      Measured next = measure(stage.kernels, spp, seed++);
      double ratio = 4.0 * next.mse / prev.mse;
      double rel_se = std::hypot(next.mse_se / next.mse, prev.mse_se / prev.mse);
      INFO(stage.name << ": MSE " << prev.mse << " at " << spp / 4 << " spp, " << next.mse << " at " << spp
                      << " spp; 4 x ratio " << ratio << " +- " << rel_se << " (relative)");
      CHECK(std::abs(ratio - 1.0) < z * rel_se * ratio);
      prev = next;
    }
  }
}

}  // namespace test_convergence
