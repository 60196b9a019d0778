// Spherical triangles (common/kernel/spherical_triangle.glsl), of stage5_mis's light-sampling
// machinery (issue #18, its list of tests; beyond the article), compiled as the CPU kernels
// compile it (the GPU compiles the same source): Van Oosterom and Strackee's solid angle
// against the angle excess in long double, from tiny triangles to nearly a hemisphere; and
// Arvo's 1995 sampling, its two steps (the sub-triangle's area, the cosine along the arc)
// within 1e-4 of the exact mapping; over random triangles of solid angle
// kMinSphericalTriangle to kMaxSphericalTriangle, round, skewed and slivers
// (tests/support/spherical_triangles.h). Where its samples fall (uniform, inside the
// triangle): test_spherical_triangle_sampling.cpp. Tags: [solid_angle] the tests of the
// sampling by solid angle, which call none of lab 6's functions.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
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

TEST_CASE("spherical triangles: the solid angle matches the angle excess, from tiny triangles to nearly a hemisphere",
          "[stage5][solid_angle]") {
  // spherical_triangle's tan(omega / 2) = |a . (b x c)| / (1 + a.b + b.c + c.a) in
  // float against Girard's A + B + C - pi in long double, on the same float vectors. In
  // float the triple product of nearly parallel unit vectors has an absolute error of up to
  // a few 1e-8 (products of unit components, eps = 6e-8): up to 1e-4 of the solid angle near
  // 1e-3 sr (measured: 2e-5), where the kernel begins to sample by solid angle
  // (kMinSphericalTriangle; by area below). Required: within 1e-4 relative from 1e-3 sr up to
  // nearly 2 pi, and within 2e-7 sr absolute below (where the solid angle only decides which
  // sampler to use).
  Rng r(test_seed(6100));
  double worst_relative = 0.0, worst_absolute_tiny = 0.0;
  int count = 0;
  std::vector<double> targets = {1e-9, 1e-7, 1e-6, 1e-5, 1e-4, 3e-4};
  for (double a : sampled_areas(15)) targets.push_back(a);
  for (double a : {6.22, 6.25, 6.27, 6.28}) targets.push_back(a);  // nearly a hemisphere (2 pi = 6.2832)
  for (double target : targets) {
    for (Shape shape : {Shape::kRound, Shape::kSkewed, Shape::kSliver}) {
      if (shape == Shape::kSliver && target > 0.3) continue;
      for (int rep = 0; rep < 20; rep++) {
        Tri t = make_triangle(target, shape, r);
        double want = double(t.area), got = double(kernel_area(t));
        INFO(describe(t) << "; kernel " << got);
        REQUIRE(std::isfinite(got));
        if (want >= double(kernel::kMinSphericalTriangle)) {
          double rel = std::abs(got - want) / want;
          worst_relative = std::max(worst_relative, rel);
          CHECK(rel <= 1e-4);
        } else {
          double abs_err = std::abs(got - want);
          worst_absolute_tiny = std::max(worst_absolute_tiny, abs_err);
          CHECK(abs_err <= 2e-7);
        }
        count++;
      }
    }
  }
  INFO(count << " triangles: worst relative error from 1e-3 sr " << worst_relative << ", worst absolute below "
             << worst_absolute_tiny);
  CHECK(count > 500);
}

TEST_CASE("spherical triangles: Arvo's two steps hold within 1e-4 (the sub-triangle's solid angle, the cosine along its arc)",
          "[stage5][solid_angle]") {
  // Arvo's mapping, exactly: u.x picks the point c' on the arc a..c for which the triangle
  // a, b, c' has u.x times the solid angle (c' = the sample at u.y = 1); u.y places the
  // sample on the arc b..c' with 1 - cos(angle from b) = u.y (1 - cos(b, c')). Both are the
  // sampler's CDFs, checked here in long double to 1e-4 of their range: at the float
  // solid angle the kernel passes (its own error included), for every triangle of the
  // chi-square test's kind, on a 17 x 17 grid of u. The sample must also lie on the arc
  // b..c' (within 1e-4 of the triangle's size) — what makes the two CDFs the whole mapping.
  Rng r(test_seed(6300));
  std::vector<Tri> tris = test_triangles(r, 12);
  double worst_x = 0.0, worst_y = 0.0, worst_arc = 0.0;
  for (const Tri& t : tris) {
    float area = kernel_area(t);
    L3 a = normalized(ld(t.a)), b = normalized(ld(t.b));
    long double size = std::sqrt(t.area);  // the triangle's angular size, roughly
    double tri_x = 0.0, tri_y = 0.0, tri_arc = 0.0;  // this triangle's worst errors, and where
    float at_x = 0.0f, at_y_x = 0.0f, at_y_y = 0.0f;
    for (int i = 0; i <= 16; i++) {
      float ux = float(i) / 16.0f;
      L3 c_sub = normalized(ld(kernel_sample(t, area, ux, 1.0f)));
      double ex = std::abs(double(vos_area(a, b, c_sub) / t.area) - ux);
      if (!(ex <= tri_x)) tri_x = ex, at_x = ux;
      long double range = 0.5L * dot(c_sub - b, c_sub - b);  // 1 - cos(b, c')
      L3 arc_normal = cross(b, c_sub);
      for (int j = 0; j <= 16; j++) {
        float uy = float(j) / 16.0f;
        L3 w = normalized(ld(kernel_sample(t, area, ux, uy)));
        long double one_minus_cos = 0.5L * dot(w - b, w - b);
        double ey = range > 0.0L ? double(std::abs(one_minus_cos - uy * range) / range) : 0.0;
        double arc = length(arc_normal) > 0.0L ? double(std::abs(dot(w, arc_normal)) / length(arc_normal) / size) : 0.0;
        if (!(ey <= tri_y)) tri_y = ey, at_y_x = ux, at_y_y = uy;
        if (!(arc <= tri_arc)) tri_arc = arc;
      }
    }
    INFO(describe(t) << ": the sub-triangle's share is off by " << tri_x << " at u.x " << at_x
                     << "; 1 - cos from b by " << tri_y << " of its range at u (" << at_y_x << ", " << at_y_y
                     << "); off the arc b..c' by " << tri_arc << " of the triangle's size");
    CHECK(tri_x <= 1e-4);
    CHECK(tri_y <= 1e-4);
    CHECK(tri_arc <= 1e-4);
    worst_x = std::max(worst_x, tri_x), worst_y = std::max(worst_y, tri_y), worst_arc = std::max(worst_arc, tri_arc);
  }
  INFO(tris.size() << " triangles: worst CDF errors u.x " << worst_x << ", u.y " << worst_y << ", off the arc " << worst_arc);
  CHECK(tris.size() >= 20);
}
