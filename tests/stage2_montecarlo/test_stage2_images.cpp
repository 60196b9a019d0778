// stage2_montecarlo (Eq. 3) against images known in closed form, on the backend under
// test (pt_tests: CPU, pt_gpu_tests: Vulkan). Tolerances come from the variance the film
// estimates (tests/support/analytic_suite.h, image_checks.h).
#include <catch2/catch.hpp>

#include "common/kernel/scene_types.h"
#include "stage2_montecarlo/kernels.h"
#include "tests/support/analytic_suite.h"
#include "tests/support/test_render.h"

using namespace pt;
using namespace pt::test;

TEST_CASE("stage2: furnace box, albedo 0.5, emission 1: every pixel is Le / (1 - albedo) = 2",
          "[stage2][statistical][analytic]") {
  check_furnace(stage2::kernels(), 0.5f, kRouletteFixed, test_seed(100));
}

TEST_CASE("stage2: a diffuse sphere under a uniform sky is albedo x sky, the sky elsewhere",
          "[stage2][statistical][analytic]") {
  check_sky_sphere(stage2::kernels(), test_seed(200));
}

TEST_CASE("stage2: a diffuse floor under a square light matches Lambert's formula pixel by pixel",
          "[stage2][statistical][analytic]") {
  check_floor_light(stage2::kernels(), test_seed(300));
}

TEST_CASE("stage2: a mirror reflects an emitter straight back as F0 x Le", "[stage2][statistical][analytic]") {
  check_mirror(stage2::kernels(), test_seed(400));
}

TEST_CASE("stage2: a glass slab of ior 1 is invisible; of ior 1.5 it transmits (1 - R) / (1 + R)",
          "[stage2][statistical][analytic]") {
  check_glass_slab(stage2::kernels(), 1.0f, test_seed(500));
  check_glass_slab(stage2::kernels(), 1.5f, test_seed(500));
}
