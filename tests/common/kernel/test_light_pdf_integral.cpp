// The light samplers' pdfs (common/kernel/lights.glsl), of stage5_mis's light-sampling
// machinery (issue #18, its list of tests; beyond the article), compiled as the CPU kernels
// compile it (the GPU compiles the same source): each sampler's pdf integrates to 1 (the
// mean of 1/pdf is the light's solid angle), for triangles by solid angle and by area
// (random triangles, tests/support/spherical_triangles.h), and spheres from outside and
// inside. Tags: [solid_angle] the tests of the sampling by solid angle, which call none of
// lab 6's functions.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "common/scene/scene.h"
#include "cpu/kernel_prelude.h"
#include "tests/support/statistics.h"
#include "tests/support/test_render.h"

namespace {  // internal linkage: each test file compiles its own copy of the kernel code
namespace kernel {
#include "tests/support/light_kernel.h"
}  // namespace kernel
}  // namespace
#include "tests/support/spherical_triangles.h"  // after the kernel: it calls kernel::spherical_triangle

using namespace pt::test;

TEST_CASE("light sampling by solid angle: the mean of 1/pdf is the light's solid angle (each sampler's pdf integrates to 1)",
          "[stage5][solid_angle][statistical]") {
  // E[1/pdf] over a sampler's directions is the measure of the set it samples: the triangle's
  // solid angle (long double, from the float vertices), the sphere's cone 2 pi (1 - cos) from
  // outside, 4 pi from inside. By solid angle, and from outside the sphere, every sample's
  // 1/pdf is that constant, and no sample may be lost (pdf 0). By area (a triangle that
  // lights.glsl leaves to its area: small, distant, or nearly a hemisphere) and from inside
  // the sphere, 1/pdf is random. Each mean must lie within 1e-4 relative (float rounding of
  // the solid angle) plus z standard errors, z at an overall 1e-3 (Šidák over the 32 means
  // at most of this test).
  Rng r(test_seed(6700));
  const double z = normal_two_sided_quantile(sidak_alpha(1e-3, 32.0));
  auto one_light = [](pt::Scene& s) {
    pt::build_light_table(s);
    REQUIRE(s.lights.size() == 1);
    kernel::bind_scene(s);
  };
  auto mean_inverse_pdf = [](glm::vec3 p, int n, int& lost, double& se) {
    double sum = 0.0, sum2 = 0.0;
    lost = 0;
    for (int i = 0; i < n; i++) {
      kernel::LightSample ls = kernel::sample_light_by(p, glm::vec3(0, 1, 0), kernel::kTriangleBySolidAngle);
      double inv = ls.pdf > 0.0f ? 1.0 / double(ls.pdf) : 0.0;
      lost += !(ls.pdf > 0.0f);
      sum += inv, sum2 += inv * inv;
    }
    double mean = sum / n;
    se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
    return mean;
  };
  kernel::rng_seed(7u, 8u, test_seed(6710));
  SECTION("triangles of 1e-3 to 6.2 sr at distances 0.2 to 5: the mean of 1/pdf is the solid angle") {
    int tested = 0, constant = 0;
    for (const Tri& t : test_triangles(r, 8)) {
      // A two-sided planar triangle at random distances along the spherical one's vertices.
      glm::vec3 p(0.3f, -0.2f, 0.1f);
      pt::Scene s;
      uint lamp = s.add_material(pt::make_diffuse(glm::vec3(0.0f), glm::vec3(1.0f), true));
      s.add_triangle(p + float(r.between(0.2, 5.0)) * t.a, p + float(r.between(0.2, 5.0)) * t.b,
                     p + float(r.between(0.2, 5.0)) * t.c, lamp);
      one_light(s);
      const pt::Triangle& tri = s.triangles[0];
      double want = double(excess_area(ld(tri.p0) - ld(p), ld(tri.p1) - ld(p), ld(tri.p2) - ld(p)));
      if (want < double(kernel::kMinSphericalTriangle) || want > double(kernel::kMaxSphericalTriangle)) continue;
      int lost;
      double se, mean = mean_inverse_pdf(p, 4000, lost, se);
      INFO(describe(t) << "; mean 1/pdf " << mean << " +- " << se << ", solid angle " << want);
      CHECK(lost == 0);
      CHECK(std::abs(mean - want) <= z * se + 1e-4 * want);
      tested++;
      constant += se <= 1e-6 * mean;  // every sample drawn by solid angle: one value
    }
    INFO(constant << " of " << tested << " triangles sampled by solid angle");
    CHECK(tested >= 15);
    CHECK(constant >= 5);
  }
  SECTION("a triangle below 1e-3 sr, sampled by its area: E[1/pdf] is its solid angle") {
    glm::vec3 p(0.0f), a(0.05f, 4.0f, -0.04f), b(-0.03f, 4.1f, 0.02f), c(0.04f, 3.9f, 0.05f);
    pt::Scene s;
    uint lamp = s.add_material(pt::make_diffuse(glm::vec3(0.0f), glm::vec3(1.0f), true));
    s.add_triangle(a, b, c, lamp);
    one_light(s);
    double want = double(excess_area(ld(a), ld(b), ld(c)));
    REQUIRE(want < double(kernel::kMinSphericalTriangle));
    int lost;
    double se, mean = mean_inverse_pdf(p, 200000, lost, se);
    INFO("mean 1/pdf " << mean << " +- " << se << ", solid angle " << want);
    CHECK(lost == 0);
    CHECK(std::abs(mean - want) <= z * se + 1e-5 * want);
  }
  SECTION("a sphere from outside (near and 1000 radii away: every 1/pdf is its cone) and from inside (E[1/pdf] = 4 pi)") {
    pt::Scene s;
    uint lamp = s.add_material(pt::make_diffuse(glm::vec3(0.0f), glm::vec3(1.0f), true));
    glm::vec3 center(0.0f, 2.0f, 0.0f);
    const float radius = 0.5f;
    s.add_sphere(center, radius, lamp);
    one_light(s);
    for (double distance : {0.51, 0.6, 1.0, 3.0, 50.0, 500.0}) {
      glm::vec3 p = center - glm::vec3(float(distance), 0.0f, 0.0f);
      double d = double(center.x - p.x);
      double sin2 = double(radius) * radius / (d * d), want = 2.0 * M_PI * sin2 / (1.0 + std::sqrt(1.0 - sin2));
      int lost;
      double se, mean = mean_inverse_pdf(p, 200, lost, se);
      INFO("distance " << distance << ": mean 1/pdf " << mean << ", cone " << want);
      CHECK(lost == 0);
      CHECK(mean == Approx(want).epsilon(1e-4));
    }
    glm::vec3 inside = center + glm::vec3(0.1f, -0.2f, 0.15f);
    int lost;
    double se, mean = mean_inverse_pdf(inside, 200000, lost, se);
    INFO("from inside: mean 1/pdf " << mean << " +- " << se << ", 4 pi " << 4.0 * M_PI);
    CHECK(lost == 0);
    CHECK(std::abs(mean - 4.0 * M_PI) <= z * se + 1e-5 * 4.0 * M_PI);
  }
}
