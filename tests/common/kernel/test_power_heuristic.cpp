// The power heuristic (common/kernel/mis.glsl), stage5_mis's weights (issue #18, its list of
// tests; beyond the article), compiled as the CPU kernels compile it (the GPU compiles the
// same source): the two weights sum to 1, never NaN, for pdfs from 0 to 3e38. Tags: [mis]
// marks the tests of lab 6's functions (docs/labs/lab6.md: power_heuristic), which grade it.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <vector>

#include "common/scene/scene.h"
#include "cpu/kernel_prelude.h"
#include "tests/support/test_render.h"

namespace {  // internal linkage: each test file compiles its own copy of the kernel code
namespace kernel {
#include "tests/support/light_kernel.h"
}  // namespace kernel
}  // namespace
#include "tests/support/spherical_triangles.h"  // after the kernel: it calls kernel::spherical_triangle

using namespace pt::test;

TEST_CASE("MIS: the power heuristic's two weights sum to 1 and are never NaN, for pdfs from 0 to 3e38",
          "[stage5][mis]") {
  // w(a, b) + w(b, a) = a^2 / (a^2 + b^2) + b^2 / (b^2 + a^2) = 1 whenever either strategy
  // can sample (a or b > 0), within float rounding (a few ulps of 1); both 0 where neither
  // can. Pairs of random pdfs log-uniform over 1e-40 (subnormal) .. 3e38 and the special
  // values 0, the smallest subnormal, 1e-30, 1, 1e30, FLT_MAX and infinity (one side only:
  // infinity against infinity has no ratio).
  Rng r(test_seed(6600));
  std::vector<float> special = {0.0f, std::numeric_limits<float>::denorm_min(), 1e-30f, 1.0f, 1e30f,
                                std::numeric_limits<float>::max(), std::numeric_limits<float>::infinity()};
  auto check_pair = [](float a, float b) {
    float wa = kernel::power_heuristic(a, b), wb = kernel::power_heuristic(b, a);
    INFO("pdfs " << a << " and " << b << ": weights " << wa << " and " << wb);
    bool ok = !std::isnan(wa) && !std::isnan(wb) && wa >= 0.0f && wa <= 1.0f && wb >= 0.0f && wb <= 1.0f;
    if (a > 0.0f || b > 0.0f) ok = ok && std::abs(double(wa) + double(wb) - 1.0) <= 1e-6;
    else ok = ok && wa == 0.0f && wb == 0.0f;
    if (!ok) FAIL_CHECK("weights do not sum as they must");
    return ok;
  };
  int pairs = 0;
  for (float a : special)
    for (float b : special) {
      if (std::isinf(a) && std::isinf(b)) continue;
      check_pair(a, b), pairs++;
    }
  for (int i = 0; i < 200000; i++) {
    float a = float(std::pow(10.0, r.between(-40.0, 38.5))), b = float(std::pow(10.0, r.between(-40.0, 38.5)));
    if (i % 3 == 0) b = a * float(r.between(0.5, 2.0));  // close pdfs, where the weights are near 1/2
    if (i % 7 == 0) b = special[std::size_t(r.uniform() * (special.size() - 1))];  // a finite special value
    check_pair(a, b), pairs++;
  }
  CHECK(kernel::power_heuristic(1.0f, 1.0f) == 0.5f);
  CHECK(kernel::power_heuristic(3.0f, 1.0f) == Approx(0.9).epsilon(1e-6));
  CHECK(pairs > 200000);
}
