// common/kernel/float_math.glsl: the kernel's own sin, cos and atan (stage5_mis's spherical
// triangles need them to a few float ulps, which Vulkan's built-ins do not promise), against
// the C library's in double, over their whole domains and near the points where the range
// reduction switches.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "cpu/kernel_prelude.h"

namespace {  // internal linkage: each test file compiles its own copy of the kernel code
namespace kernel {
using namespace pt::glsl;
#include "common/kernel/float_math.glsl"
}  // namespace kernel

// The error of a float result in units of the float spacing at the true value (at least the
// spacing of 1e-30, so that a true 0 has a scale).
double ulps(float got, double want) {
  double scale = std::max(std::abs(want), 1e-30);
  double spacing = std::ldexp(1.0, std::ilogb(scale) - 23);
  return std::abs(double(got) - want) / spacing;
}
}  // namespace

TEST_CASE("float_math: sin and cos within 4 ulps over [0, 5 pi / 4], small arguments in relative terms",
          "[float_math]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uniform(0.0f, 3.92699082f);
  double worst_sin = 0, worst_cos = 0;
  auto check = [&](float h) {
    glm::vec2 sc = kernel::sin_cos(h);
    worst_sin = std::max(worst_sin, ulps(sc.x, std::sin(double(h))));
    // cos crosses 0 at pi/2: there its error is judged against the spacing of sin's scale.
    double c = std::cos(double(h));
    worst_cos = std::max(worst_cos, std::abs(double(sc.y) - c) / std::ldexp(1.0, std::ilogb(std::max(std::abs(c), 1e-3)) - 23));
  };
  for (int i = 0; i < 200000; i++) check(uniform(rng));
  for (float h : {0.0f, 1e-30f, 1e-7f, 1e-4f, 0.785398163f, 0.7853982f, 2.35619449f, 2.3561945f, 1.57079637f, 3.14159274f,
                  3.1415925f, 3.92699082f}) {
    check(h);
  }
  INFO("worst sin error " << worst_sin << " ulps, cos " << worst_cos);
  CHECK(worst_sin <= 4.0);
  CHECK(worst_cos <= 4.0);
}

TEST_CASE("float_math: atan2 of the upper half plane within 4 ulps, from tiny angles to pi", "[float_math]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> angle(0.0f, 3.14159265f);
  std::uniform_real_distribution<float> exponent(-30.0f, 30.0f);
  double worst = 0;
  auto check = [&](float y, float x) {
    worst = std::max(worst, ulps(kernel::atan2_upper(y, x), std::atan2(double(y), double(x))));
  };
  for (int i = 0; i < 200000; i++) {
    float a = angle(rng);
    float r = std::exp2(exponent(rng));
    check(std::abs(r * std::sin(a)), r * std::cos(a));
  }
  for (float t : {1e-30f, 1e-7f, 1e-3f, 0.414213562f, 0.4142136f, 1.0f, 2.41421356f, 2.4142137f, 1e7f}) {
    check(t, 1.0f);   // the reduction's switch points
    check(1.0f, -t);  // the left half
  }
  check(0.0f, 1.0f);
  check(0.0f, -1.0f);
  INFO("worst atan2 error " << worst << " ulps");
  CHECK(worst <= 4.0);
}
