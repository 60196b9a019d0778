// stage5_mis (beyond the article: multiple importance sampling of a light sample and a BSDF
// sample at every non-delta hit, power heuristic) against images known in closed form, on
// the backend under test; issue #18's list of tests. Every analytic image of stage4: the
// spherical furnace, the one-bounce box furnace, the sky sphere, Lambert's square light at
// three sizes and the triangle light, the mirror, the glass slab, the point lights; then
// what stage4 could not pass: the box furnace with every bounce, whose error now halves as
// the samples quadruple (a finite variance); and stage5 against stage3 on the Cornell box,
// region by region (t-tests).
#include <catch2/catch.hpp>

#include <cmath>
#include <sstream>
#include <vector>

#include "common/scene/analytic_scenes.h"
#include "common/scene/scene_loading.h"
#include "common/kernel/scene_types.h"
#include "stage3_importance/kernels.h"
#include "stage5_mis/kernels.h"
#include "tests/support/analytic_suite.h"
#include "tests/support/lambert.h"
#include "tests/support/statistics.h"
#include "tests/support/test_render.h"

using namespace pt;
using namespace pt::test;

TEST_CASE("stage5: furnace sphere whose inside emits: Le / (1 - albedo) at albedo 0.5 and 0.8",
          "[stage5][statistical][analytic]") {
  check_furnace_sphere(stage5::kernels(), 0.5f, test_seed(5100));
  check_furnace_sphere(stage5::kernels(), 0.8f, test_seed(5150));
}

TEST_CASE("stage5: the furnace with one bounce only is Le (1 + albedo): the emission the last ray finds counts once",
          "[stage5][statistical][analytic]") {
  // The depth cap ends the path after the emission its last ray found: the camera hit's Le,
  // and its direct light from both strategies, weighted to sum to albedo Le.
  check_one_bounce_furnace(stage5::kernels(), test_seed(5175));
}

TEST_CASE("stage5: the box furnace with every bounce is Le / (1 - albedo) at albedo 0.5 and 0.8 (stage4's light sampling "
          "has infinite variance there)",
          "[stage5][statistical][analytic]") {
  // Near the box's edges stage4's cos_x cos_y / d^2 / pdf is unbounded (its second moment
  // diverges; test_stage4_images.cpp). Weighted by the power heuristic a light sample
  // contributes f Le cos p_l / (p_l^2 + p_b^2) <= f Le cos / p_b = albedo Le with cosine
  // sampling, and so does a BSDF sample: every bounce's estimate is bounded, and the
  // variance-derived tolerances hold.
  check_furnace(stage5::kernels(), 0.5f, kRouletteThroughput, test_seed(5180));
  check_furnace(stage5::kernels(), 0.8f, kRouletteThroughput, test_seed(5190));
}

namespace {

// The box furnace (albedo 0.5, answer 2) at 16 x 16 pixels rendered with `seeds` seeds
// (from `seed` on) at each sample count with independent samples: per sample count, the
// mean squared error of the pixels against the closed form over all pixel-renders, and
// the relative variance of that mean (from the spread of the squared errors).
struct FurnaceErrors {
  std::vector<double> mse, relvar;
};

FurnaceErrors furnace_errors(const StageKernels& kernels, const std::vector<std::uint64_t>& spps, int seeds,
                             std::uint32_t seed) {
  analytic::FurnaceScene f;
  const double want = f.emission / (1.0 - f.albedo);
  const int size = 16;
  FurnaceErrors out;
  for (std::uint64_t spp : spps) {
    double sum = 0.0, sum2 = 0.0;
    int count = 0;
    for (int k = 0; k < seeds; k++) {
      RenderSettings s = settings(size, size, spp, seed++);
      s.roulette = kRouletteThroughput;
      s.sampler = kSamplerIndependent;
      Film film = render_on_test_backend(kernels, analytic::make_furnace(f), s).film;
      for (int y = 0; y < size; y++)
        for (int x = 0; x < size; x++) {
          double e = luminance(film.mean(x, y)) - want, e2 = e * e;
          sum += e2, sum2 += e2 * e2, count++;
        }
    }
    double m = sum / count, v = (sum2 / count - m * m) / (count - 1);  // v: the variance of the mean m
    out.mse.push_back(m);
    out.relvar.push_back(v / (m * m));
  }
  return out;
}

}  // namespace

TEST_CASE("stage5: the box furnace's per-pixel error halves (+-15%) as the samples quadruple, 64 to 1024 spp",
          "[stage5][statistical][analytic]") {
  // Issue #18: "relative error halves (+-15%) as samples quadruple". With a finite variance
  // sigma^2 and independent samples (--sampler independent), the mean squared error of a
  // pixel is exactly sigma^2 / N, so the RMS error over pixels falls by exactly 1/2 from N to
  // 4N. Measured on builtin:furnace (albedo 0.5, answer 2), 16 x 16 pixels, 6 seeds per
  // sample count, against the closed form: the mean squared error over the 1536
  // pixel-renders at 64, 256 and 1024 spp, and the two ratios of RMS errors. Each ratio's
  // standard error comes from the spread of the squared errors (delta method); the ratio
  // must lie within the Šidák-corrected normal quantile (overall 1e-3, 2 ratios) of 1/2,
  // and that interval must be inside the issue's +-15% (else the test would not resolve
  // it). stage4 on the same box has an unbounded estimate near the edges, and no such rate.
  const std::vector<std::uint64_t> spps = {64, 256, 1024};
  const int seeds = 6;
  const double z = normal_two_sided_quantile(sidak_alpha(1e-3, double(spps.size() - 1)));
  FurnaceErrors e = furnace_errors(stage5::kernels(), spps, seeds, test_seed(5200));
  std::ostringstream table;
  std::vector<double> ns(spps.begin(), spps.end()), rmse;
  for (std::size_t i = 0; i < spps.size(); i++) {
    rmse.push_back(std::sqrt(e.mse[i]));
    table << "\n  " << spps[i] << " spp: RMS error " << rmse[i] << " (+-" << 50.0 * std::sqrt(e.relvar[i]) << "%)";
  }
  INFO("RMS error against 2 over " << seeds * 256 << " pixel-renders each:" << table.str()
                                   << "\nslope of log RMS error over log N: " << log_slope(ns, rmse));
  for (std::size_t i = 0; i + 1 < spps.size(); i++) {
    double ratio = rmse[i + 1] / rmse[i];
    double se = ratio * 0.5 * std::sqrt(e.relvar[i] + e.relvar[i + 1]);
    INFO(spps[i] << " to " << spps[i + 1] << " spp: the RMS error falls by " << ratio << " +- " << se << ", allowed 0.5 +- "
                 << z * se << " (and at most 0.075)");
    CHECK(std::abs(ratio - 0.5) <= z * se);
    CHECK(z * se <= 0.15 * 0.5);
  }
}

TEST_CASE("stage5: a diffuse sphere under a uniform sky is albedo x sky", "[stage5][statistical][analytic]") {
  check_sky_sphere(stage5::kernels(), test_seed(5300));
}

TEST_CASE("stage5: a diffuse floor under a small, the default and a large square light, and under a triangle light, "
          "matches Lambert's formula",
          "[stage5][statistical][analytic]") {
  // builtin:floor_small_light (half-size 0.1: light sampling's case), builtin:floor_light
  // (0.5) and builtin:floor_large_light (2: BSDF sampling's case, where the light's corners
  // are nearly overhead), the same power; and the default square's triangle half. The
  // light's solid angle from the floor spans the area fallback (the small light's far
  // corners, below 1e-3 sr) up to several sr. The image mean must match with no floor on
  // the tolerance: the Sobol sampler's batch means resolve 2e-6 relative here, and before
  // the spherical triangles took their sin, cos and atan from float_math.glsl, lavapipe's
  // built-ins biased the mean by -2.2e-5 (t = -9.8); now 20 seed offsets pass on both
  // backends.
  const int size = 16;
  std::uint32_t seed = test_seed(5400);
  for (float half : {analytic::kSmallLightHalf, 0.5f, analytic::kLargeLightHalf}) {
    for (bool triangle : {false, true}) {
      if (triangle && half != 0.5f) continue;
      analytic::FloorLightScene a;
      a.emission *= (a.light_half * a.light_half) / (half * half);  // as builtin:floor_small_light and _large_light
      a.light_half = half;
      a.triangle = triangle;
      INFO("light half-size " << half << (triangle ? ", the triangle" : ", the square"));
      check_scene(stage5::kernels(), analytic::make_floor_light(a), floor_light_image(a, size),
                  settings(size, size, 256, seed));
      seed += 10;
    }
  }
}

TEST_CASE("stage5: a one-sided light turned away from the floor lights none of it: every pixel is 0",
          "[stage5][analytic]") {
  check_light_turned_away(stage5::kernels(), test_seed(2860), false);
  check_light_turned_away(stage5::kernels(), test_seed(2870), true);
}

TEST_CASE("stage5: a mirror reflects an emitter straight back as F0 x Le (emission after a delta bounce)",
          "[stage5][statistical][analytic]") {
  check_mirror(stage5::kernels(), test_seed(5500));
}

TEST_CASE("stage5: a glass slab of ior 1 is invisible; of ior 1.5 it transmits (1 - R) / (1 + R)",
          "[stage5][statistical][analytic]") {
  check_glass_slab(stage5::kernels(), 1.0f, test_seed(5600));
  check_glass_slab(stage5::kernels(), 1.5f, test_seed(5600));
}

TEST_CASE("stage5: a point light above a diffuse floor gives albedo I cos / (pi d^2) (a delta light: the light sample alone)",
          "[stage5][statistical][analytic]") {
  check_point_floor(stage5::kernels(), 16, test_seed(5700));
}

TEST_CASE("stage5: a spot light and a directional light above a diffuse floor (delta lights: the light sample alone)",
          "[stage5][statistical][analytic][punctual]") {
  check_point_floor(stage5::kernels(), 16, test_seed(5710), kPunctualSpot);
  check_point_floor(stage5::kernels(), 8, test_seed(5720), kPunctualDirectional);
}

TEST_CASE("stage5: inside a diffuse sphere lit by a point light of intensity pi at its centre every pixel is 1",
          "[stage5][statistical][analytic]") {
  check_point_in_sphere(stage5::kernels(), test_seed(5800));
}

TEST_CASE("stage5 and stage3 agree on the Cornell box, over the image and region by region (t-tests)",
          "[stage3][stage5][statistical]") {
  check_agree_on_cornell(stage3::kernels(), stage5::kernels(), test_seed(5900));
}

