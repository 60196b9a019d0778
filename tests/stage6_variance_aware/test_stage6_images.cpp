// stage6_variance_aware (beyond the article: stage5 plus the roulette after emission and the
// pilot's MIS weights) against images known in closed form, on the CPU: each fails if the
// roulette after emission drops or double-counts a last ray's emission, or if the pilot's
// factors break the weights' sum to 1 (the glass cases: test_stage6_roulette.cpp).
#include <catch2/catch.hpp>

#include <cmath>

#include "common/scene/analytic_scenes.h"
#include "stage6_variance_aware/kernels.h"
#include "tests/support/analytic_suite.h"
#include "tests/support/test_render.h"

using namespace pt;
using namespace pt::test;

TEST_CASE("stage6: the box furnace with every bounce is Le / (1 - albedo) = 2 at albedo 0.5 under either roulette: "
          "the emission of a path's last ray counts once",
          "[stage6][statistical][analytic]") {
  // Every wall emits: every ray a path traces finds Le, the last one too. The roulette's
  // verdict on the path beyond a hit is drawn before the ray is traced and applied after the
  // emission that ray finds: dropping that emission, or counting it twice (once with the
  // survivor's 1 / p, once without), or forgetting the 1 / p, moves the image by a share of
  // Le per bounce that the roulette ends (29% of the paths per bounce at albedo 0.5 under
  // the square-root roulette, half under the fixed one).
  // (Albedo 0.8, longer paths: the furnace sphere below.)
  check_furnace(stage6::kernels(), 0.5f, kRouletteThroughput, test_seed(6100));
  check_furnace(stage6::kernels(), 0.5f, kRouletteFixed, test_seed(6120));
}

TEST_CASE("stage6: the furnace with one bounce only is Le (1 + albedo): the depth cap ends the path after the "
          "emission its last ray found",
          "[stage6][statistical][analytic]") {
  check_one_bounce_furnace(stage6::kernels(), test_seed(6175));
}

TEST_CASE("stage6: furnace sphere whose inside emits: Le / (1 - albedo) at albedo 0.8", "[stage6][statistical][analytic]") {
  // One sphere light: may_find_emission tries it for every ray the roulette ended, and
  // every ray from inside meets it.
  check_furnace_sphere(stage6::kernels(), 0.8f, test_seed(6150));
}

TEST_CASE("stage6: a diffuse floor under a small and a large square light matches Lambert's formula with the "
          "pilot's own factors",
          "[stage6][statistical][analytic]") {
  // The pilot chooses a factor far from 1 on both (test_stage6_pilot.cpp): the light sample
  // counts x64 or more under the small light, x4 or more under the large one, where the BSDF
  // sample's weight is then small but not 0 near the light's corners. The weights must still
  // sum to 1 there, and the roulette after emission must keep each vertex's two shares together.
  const int size = 16;
  std::uint32_t seed = test_seed(6400);
  for (float half : {analytic::kSmallLightHalf, analytic::kLargeLightHalf}) {
    analytic::FloorLightScene a;
    a.emission *= (a.light_half * a.light_half) / (half * half);  // as builtin:floor_small_light and _large_light
    a.light_half = half;
    INFO("light half-size " << half);
    RenderSettings s = settings(size, size, 256, seed);
    s.roulette = kRouletteThroughput;
    check_scene(stage6::kernels(), analytic::make_floor_light(a), floor_light_image(a, size), s);
    seed += 10;
  }
}
