// Numerical stability of light transport at its extremes, as images on the backend under test
// (pt_tests: CPU, pt_gpu_tests: Vulkan): furnaces of albedo 0.99 and 0.999, the unbounded second
// moment of the article's fixed roulette (errata 3-4), radiance from 1e-20 to 1e20, and a square
// light shrunk to side 1e-6 (stage4's light sampling, Eq. 5). Surfaces: test_extremes_surfaces.cpp.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "common/scene/analytic_scenes.h"
#include "common/kernel/scene_types.h"
#include "stage2_montecarlo/kernels.h"
#include "stage3_importance/kernels.h"
#include "stage4_direct_indirect/kernels.h"
#include "tests/support/analytic_suite.h"
#include "tests/support/lambert.h"
#include "tests/support/test_render.h"

using namespace pt;
using namespace pt::test;

namespace {

// Mean over the pixels of the per-sample luminance variance the film estimated.
double mean_sample_variance(const Film& film) {
  double v = 0.0;
  for (int y = 0; y < film.height(); y++)
    for (int x = 0; x < film.width(); x++) v += film.sample_variance(x, y);
  return v / (double(film.width()) * film.height());
}

}  // namespace

TEST_CASE("stability: furnace boxes of albedo 0.99 and 0.999 reach Le / (1 - albedo) on stages 3 and 4, or "
          "the backend says it could not", "[stage3][stage4][stability][statistical][analytic]") {
  // With throughput roulette a path continues with probability albedo: at 0.999 the mean
  // path has 1000 bounces, 37% of paths pass the default depth cap of 1000 (which would
  // give 1 - 0.999^1000 = 632 instead of 1000), so the cap is raised to where what it cuts,
  // 1000 x 0.999^20000 = 2e-6, is far below the noise.
  // lavapipe ends a kernel's loops after 65535 iterations in all (gpu/kernel_main.glsl): 16
  // samples of 1000 bounces over 12 triangles are far more. The GPU backend then renders
  // one sample per invocation (gpu_backend.cpp), which is enough at 0.99; a single path of
  // more than about 2700 bounces (stage4) is still cut. That pass would be wrong: the render
  // stops before it with a device error (exit 4 in the programs); a CPU never does.
  for (float albedo : {0.99f, 0.999f}) {
    for (const StageKernels& kernels : {stage3::kernels(), stage4::kernels()}) {
      analytic::FurnaceScene f;
      f.albedo = albedo;
      RenderSettings s = settings(2, 2, 64, test_seed(7000));
      s.roulette = kRouletteThroughput;
      s.depth_cap = 20000;
      double want = f.emission / (1.0 - double(f.albedo));
      INFO(kernels.name << ", albedo " << albedo << ": want " << want);
      RenderResult probe = render_on_test_backend(kernels, analytic::make_furnace(f), s);
      if (!probe.device_error.empty()) {
        CHECK(backend_under_test == "gpu");
        CHECK_THAT(probe.device_error, Catch::Matchers::Contains("cut the loops"));
        WARN(kernels.name << ", albedo " << albedo << ": " << probe.device_error << "; the "
                          << probe.film.spp() << " spp before it are not checked");
        continue;
      }
      // The probe's 256 samples know the answer to about 6% (a geometric number of surfaces,
      // its standard deviation about its mean): outside a factor 2 of it the estimator is
      // wrong, and the 8 batches after it are not rendered. A wrong one whose weights average
      // above 1 (lab 3's mutant cosine_pdf_uniform) never ends a path by the roulette, and
      // each of its renders runs every path to the cap of 20000 bounces.
      const double probe_mean = probe.film.mean_luminance();
      const bool near_answer = probe_mean >= 0.5 * want && probe_mean <= 2.0 * want;
      CHECK(near_answer);
      if (!near_answer) continue;
      check_scene(kernels, analytic::make_furnace(f), ExpectedImage(2 * 2, glm::dvec3(want)), s);
    }
  }
}

TEST_CASE("stability: the article's fixed roulette at albedo 0.999: the second moment doubles with every "
          "bounce the depth cap allows (infinite variance)", "[stage3][stability][statistical]") {
  // In the furnace box with cosine sampling every bounce weighs rho exactly and the fixed
  // roulette continues with p = 1/2, dividing by it: with depth cap D a sample is
  // S_k = sum_{j<=k} (2 rho)^j with k = min(K, D - 1), K ~ Geometric(1/2). Its second
  // moment grows by 2 rho^2 = 1.996 per bounce allowed: without a cap it is infinite, and
  // no number of samples makes the image converge at the rate 1/sqrt(n).
  const double rho = double(0.999f);
  double previous = 0.0;
  for (std::uint32_t cap : {3u, 6u, 9u}) {
    // The capped distribution in closed form: its variance and the variance estimate's
    // standard error (from the fourth central moment).
    double mean = 0.0, m2 = 0.0;
    std::vector<double> value, prob;
    for (std::uint32_t k = 0; k < cap; k++) {
      double s_k = (std::pow(2.0 * rho, k + 1.0) - 1.0) / (2.0 * rho - 1.0);
      double p_k = k + 1 < cap ? std::pow(0.5, k + 1.0) : std::pow(0.5, double(k));
      value.push_back(s_k), prob.push_back(p_k);
      mean += p_k * s_k, m2 += p_k * s_k * s_k;
    }
    double var = m2 - mean * mean, mu4 = 0.0;
    for (std::size_t i = 0; i < value.size(); i++) mu4 += prob[i] * std::pow(value[i] - mean, 4.0);
    analytic::FurnaceScene f;
    f.albedo = float(rho);
    RenderSettings s = settings(16, 16, 256, test_seed(7100));
    s.roulette = kRouletteFixed;
    s.depth_cap = cap;
    RenderResult r = render_on_test_backend(stage3::kernels(), analytic::make_furnace(f), s);
    double n = 16.0 * 16.0 * 256.0;
    double se = std::sqrt((mu4 - var * var) / n);
    double got = mean_sample_variance(r.film);
    INFO("depth cap " << cap << ": sample variance " << got << ", closed form " << var << " +- " << se
                      << ", second moment " << m2);
    CHECK(std::abs(got - var) < 5.0 * se);
    if (previous > 0.0) CHECK(m2 / previous > std::pow(1.9, 3.0));  // ~ (2 rho^2)^3 = 7.98 per 3 bounces
    previous = m2;
  }
}

TEST_CASE("stability: radiance from 1e-20 to 1e20 neither overflows nor flushes to zero in the film",
          "[stage3][stage4][stability]") {
  // The same seed renders the same paths, so the furnace at emission E is E times the one
  // at emission 1: mean and estimated variance must scale by E and E^2 (float rounding
  // only), not turn infinite (squares of 1e20 overflow a float) or zero (squares of 1e-20
  // are below the smallest float).
  for (const StageKernels& kernels : {stage3::kernels(), stage4::kernels()}) {
    analytic::FurnaceScene f;
    RenderSettings s = settings(4, 4, 64, test_seed(7200));
    s.roulette = kRouletteThroughput;
    Film unit = render_on_test_backend(kernels, analytic::make_furnace(f), s).film;
    double unit_mean = unit.mean_luminance(), unit_var = mean_sample_variance(unit);
    REQUIRE(unit_var > 0.0);
    for (double e : {1e-20, 1e-10, 1e10, 1e20}) {
      f.emission = float(e);
      RenderResult r = render_on_test_backend(kernels, analytic::make_furnace(f), s);
      double e_f = double(float(e));
      INFO(kernels.name << ", emission " << e);
      CHECK(r.counters.non_finite == 0);
      CHECK(r.film.mean_luminance() / e_f == Approx(unit_mean).epsilon(1e-5));
      CHECK(mean_sample_variance(r.film) / (e_f * e_f) == Approx(unit_var).epsilon(1e-4));
      CHECK(std::isfinite(r.film.relative_standard_error()));
      CHECK(std::isfinite(r.film.per_pixel_relative_error()));
      std::vector<float> rgb = r.film.mean_rgb();
      for (float v : rgb) {
        if (!(std::isfinite(v) && v > 0.0f)) FAIL("pixel value " << v);
      }
    }
  }
}

namespace {

// The floor of FloorLightScene under its square light shrunk to `side` at constant power:
// the emission grows as 1 / side^2.
analytic::FloorLightScene small_light(double side) {
  analytic::FloorLightScene a;
  a.light_half = float(0.5 * side);
  a.emission = glm::vec3(float(4.0 / (side * side)));
  return a;
}

// The limit of a vanishing square light of power fixed by Le A = 4: a point emitter whose
// intensity is Le A cos(theta_light) (it emits downwards only, like the square), so the
// floor's radiance is albedo / pi x Le A cos_l cos_f / d^2 = albedo Le A h^2 / (pi d^4).
ExpectedImage point_limit_image(const analytic::FloorLightScene& a, int size) {
  return expected_image(size, size, [&](double x0, double y0, double x1, double y1) {
    auto radiance = [](double sx, double sy, const void* data) {
      const analytic::FloorLightScene& a = *static_cast<const analytic::FloorLightScene*>(data);
      double h = a.light_height, x = sx * a.view_half, z = -sy * a.view_half;
      double d2 = x * x + z * z + h * h;
      return a.albedo / M_PI * 4.0 * h * h / (d2 * d2);
    };
    return glm::dvec3(rect_average(x0, y0, x1, y1, radiance, &a));
  });
}

}  // namespace

TEST_CASE("stability: a square light shrunk from side 1 to 1e-6 at constant power converges to the "
          "point-light image on stage4", "[stage4][stability][statistical][analytic]") {
  const int size = 10;
  for (double side : {1.0, 1e-2, 1e-4, 1e-6}) {
    analytic::FloorLightScene a = small_light(side);
    // Side 1: Lambert's formula for the square; below, the point limit, which differs
    // from the square's image by O(side^2) (1e-4 relative at side 1e-2).
    ExpectedImage expected = side == 1.0 ? floor_light_image(a, size) : point_limit_image(a, size);
    RenderSettings s = settings(size, size, 64, test_seed(7700));
    s.roulette = kRouletteThroughput;
    INFO("side " << side);
    check_scene(stage4::kernels(), analytic::make_floor_light(a), expected, s);
  }
}

TEST_CASE("stability: as the square light shrinks, stages 2-3 find it by chance and their variance grows "
          "as 1 / side^2; stage4's does not", "[stage2][stage3][stage4][stability][statistical]") {
  // The floor's radiance stays ~ the same; a BRDF-sampled ray hits a light of solid angle
  // ~ side^2 with probability ~ side^2 and then carries ~ 1 / side^2: the per-sample
  // variance grows as 1 / side^2. Light sampling (stage4) always reaches the light.
  auto relative_variance = [](const StageKernels& kernels, double side) {
    RenderSettings s = settings(8, 8, 512, test_seed(7800));
    s.roulette = kRouletteThroughput;
    Film film = render_on_test_backend(kernels, analytic::make_floor_light(small_light(side)), s).film;
    double m = film.mean_luminance();
    return mean_sample_variance(film) / (m * m);
  };
  double stage4_ratio = relative_variance(stage4::kernels(), 0.1) / relative_variance(stage4::kernels(), 1.0);
  INFO("stage4: relative variance at side 0.1 / side 1 = " << stage4_ratio);
  CHECK(stage4_ratio < 2.0);
  for (const StageKernels& kernels : {stage2::kernels(), stage3::kernels()}) {
    double ratio = relative_variance(kernels, 0.1) / relative_variance(kernels, 1.0);
    INFO(kernels.name << ": relative variance at side 0.1 / side 1 = " << ratio << " (1 / side^2 = 100)");
    CHECK(ratio > 30.0);
  }
}
