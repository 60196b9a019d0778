// stage5_mis (beyond the article) with a glTF file's KHR_lights_punctual lights, on the
// backend under test (issue #46): a delta light is found by the light sample alone, with
// full weight, so stage5 gives stage4's closed forms: 683 cd at height 1 above a white
// Lambert floor and 683 lux at normal incidence give 1/pi (683 lm/W), and a hard-edged spot
// (inner == outer) gives I cos / (pi d^2) inside its cone and 0 outside.
#include <catch2/catch.hpp>

#include "stage5_mis/kernels.h"
#include "tests/stage4_direct_indirect/photometric_floor.h"

using namespace pt;
using namespace pt::test;

TEST_CASE("stage5: a point light of 683 cd at height 1 above a white Lambert floor gives 1/pi straight below it",
          "[stage5][statistical][punctual][gltf]") {
  check_photometric_point(stage5::kernels(), test_seed(5960));
}

TEST_CASE("stage5: a directional light of 683 lux at normal incidence on a white Lambert floor gives 1/pi",
          "[stage5][statistical][punctual][gltf]") {
  check_photometric_sun(stage5::kernels(), test_seed(5970));
}

TEST_CASE("stage5: a hard-edged spot (inner == outer) over a floor gives I cos / (pi d^2) inside its cone, 0 outside",
          "[stage5][statistical][punctual][gltf]") {
  check_hard_spot(stage5::kernels(), test_seed(5980));
}
