// The article's printed formulas that a correct stage2 must not follow (docs/errata.md, errata
// 1, 3 and 4), each shown to matter: the printed Eq. (3) factor fails the furnace test,
// and the fixed roulette's second moment per bounce exceeds 1 at albedo 0.8 while the
// throughput roulette's does not. Also: the depth cap is a counted safety net.
#include <catch2/catch.hpp>

#include <cmath>

#include "cpu/cpu_backend.h"
#include "common/scene/analytic_scenes.h"
#include "cpu/kernel_prelude.h"
#include "stage2_montecarlo/kernels.h"
#include "tests/support/image_checks.h"
#include "tests/support/test_render.h"

// stage2's integrator built as the article prints Eq. (3): the factor 1/(2 pi N).
namespace printed {
#include "cpu/kernel_begin.h"
#include "printed/stage2_eq3.glsl"  // the integrator as the article prints it (tests/printed_formulas.cmake)
#include "cpu/kernel_end.h"
}  // namespace printed

using namespace pt;
using namespace pt::test;

TEST_CASE("stage2 erratum 1: the printed factor 1/(2 pi N) fails the furnace test, 2 pi / N passes",
          "[stage2][errata][statistical]") {
  analytic::FurnaceScene f;  // albedo 0.5, Le 1: the answer is 2
  Scene scene = analytic::make_furnace(f);
  RenderSettings s = settings(8, 8, 1024, test_seed(600));
  ExpectedImage want(64, glm::dvec3(f.emission / (1.0 - f.albedo)));

  const CpuKernel printed_cpu[] = {printed::cpu_kernel()};
  StageKernels as_printed{"stage2 as printed", printed_cpu, {}};
  Film wrong = render(*make_cpu_backend(as_printed), scene, s).film;
  CHECK_FALSE(check_pixels(wrong, want).passed());
  // The printed factor is 4 pi^2 too small per bounce: effective albedo 0.5 / (4 pi^2).
  double mean = 0.0;
  for (int i = 0; i < 64; i++) mean += wrong.mean(i % 8, i / 8).x / 64.0;
  CHECK(mean == Approx(1.0 / (1.0 - f.albedo / (4.0 * M_PI * M_PI))).epsilon(0.01));

  Film right = render(*make_cpu_backend(stage2::kernels()), scene, s).film;
  CHECK(check_pixels(right, want).passed());
}

namespace {

struct Moments {
  double mean, second, second_se;
};

// One diffuse bounce of stage2 at albedo rho, followed by the roulette, from weight 1:
// the mean and second moment of the weight the path carries on. The kernel functions are
// stage2's (compiled above): its sampler, uniform_bounce_weight (the corrected 2 pi) and
// russian_roulette, lab 2's functions.
namespace kernel = printed;
Moments bounce_moments(float rho, uint mode, std::uint32_t seed) {
  const int n = 2'000'000;
  double sum = 0.0, sum2 = 0.0, sum4 = 0.0;
  kernel::rng_seed(0u, 0u, seed);
  for (int i = 0; i < n; i++) {
    glm::vec3 wi = kernel::sample_uniform_hemisphere(kernel::rng_next_vec2());
    glm::vec3 beta = kernel::uniform_bounce_weight(kernel::lambert_brdf(glm::vec3(rho), glm::vec3(0, 0, 1), wi), wi);
    double w = double(beta.x * kernel::russian_roulette(beta, mode));
    sum += w, sum2 += w * w, sum4 += w * w * w * w;
  }
  double second = sum2 / n;
  return Moments{sum / n, second, std::sqrt((sum4 / n - second * second) / n)};
}

}  // namespace

TEST_CASE("stage2 errata 3-4: roulette is unbiased; fixed p = 1/2 has second moment > 1 per bounce at "
          "albedo 0.8, throughput roulette < 1", "[stage2][errata][statistical]") {
  const float rho = 0.8f;
  Moments fixed = bounce_moments(rho, kRouletteFixed, test_seed(700));
  Moments throughput = bounce_moments(rho, kRouletteThroughput, test_seed(701));
  // Both keep the mean (the survivor is divided by p): E = albedo.
  CHECK(fixed.mean == Approx(rho).epsilon(0.01));
  CHECK(throughput.mean == Approx(rho).epsilon(0.01));
  // Fixed: (1/p) (4 rho^2 / 3) = 8 rho^2 / 3 = 1.707 > 1: the variance grows without bound
  // with the path length. Throughput: the closed form is 0.958 < 1.
  CHECK(fixed.second == Approx(8.0 * rho * rho / 3.0).margin(5.0 * fixed.second_se));
  CHECK(fixed.second - 5.0 * fixed.second_se > 1.0);
  double c = 1.0 / (2.0 * rho);  // cos theta above which the weight 2 rho cos exceeds 1
  double closed = 2.0 * rho * c * c / 2.0 + 4.0 * rho * rho * (1.0 - c * c * c) / 3.0;
  CHECK(throughput.second == Approx(closed).margin(5.0 * throughput.second_se));
  CHECK(throughput.second + 5.0 * throughput.second_se < 1.0);
}

TEST_CASE("stage2: the depth cap is a safety net that is counted when it is hit", "[stage2]") {
  Scene scene = analytic::make_furnace({});
  RenderSettings s = settings(8, 8, 64, 3);
  s.roulette = kRouletteThroughput;  // at albedo 0.5 the weight halves: paths end within ~10 bounces
  RenderResult normal = render(*make_cpu_backend(stage2::kernels()), scene, s);
  CHECK(normal.counters.depth_cap == 0);
  s.depth_cap = 2;
  RenderResult capped = render(*make_cpu_backend(stage2::kernels()), scene, s);
  CHECK(capped.counters.depth_cap > 0);
  CHECK(capped.counters.depth_cap <= 64u * 64u);
}
