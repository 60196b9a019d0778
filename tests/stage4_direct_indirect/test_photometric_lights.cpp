// stage4_direct_indirect's light sample (Eq. 5) of a glTF file's KHR_lights_punctual lights,
// on the backend under test (issue #46): the extension's candela and lux become W/sr and
// W/m^2 at 683 lm/W, so 683 cd at height 1 above a white Lambert floor gives 1/pi below
// it, and so does 683 lux at normal incidence; a spot with inner == outer (Blender's Spot
// Blend 0) is a hard-edged cone: I cos / (pi d^2) inside it, exactly 0 outside.
#include <catch2/catch.hpp>

#include <cmath>

#include "common/scene/scene_loading.h"
#include "stage4_direct_indirect/kernels.h"
#include "tests/stage4_direct_indirect/photometric_floor.h"

using namespace pt;
using namespace pt::test;

TEST_CASE("stage4: a point light of 683 cd at height 1 above a white Lambert floor gives 1/pi straight below it",
          "[stage4][statistical][punctual][gltf]") {
  check_photometric_point(stage4::kernels(), test_seed(2900));
}

TEST_CASE("stage4: a directional light of 683 lux at normal incidence on a white Lambert floor gives 1/pi",
          "[stage4][statistical][punctual][gltf]") {
  check_photometric_sun(stage4::kernels(), test_seed(2910));
}

TEST_CASE("stage4: a hard-edged spot (inner == outer) over a floor gives I cos / (pi d^2) inside its cone, 0 outside",
          "[stage4][statistical][punctual][gltf]") {
  check_hard_spot(stage4::kernels(), test_seed(2920));
}
