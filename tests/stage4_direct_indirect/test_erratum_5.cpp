// Erratum 5: Eq. (5) as printed sums f Le cos over the lights with no geometry term and no
// pdf. Built from stage4's own integrator, it fails Lambert's formula for the floor under
// a square light, which the corrected estimator passes (test_stage4_images.cpp).
#include <catch2/catch.hpp>

#include "cpu/cpu_backend.h"
#include "common/scene/analytic_scenes.h"
#include "cpu/kernel_prelude.h"
#include "stage4_direct_indirect/kernels.h"
#include "tests/support/image_checks.h"
#include "tests/support/analytic_suite.h"
#include "tests/support/test_render.h"

namespace {
namespace eq5_printed {
#include "cpu/kernel_begin.h"
#include "printed/stage4_eq5.glsl"  // the integrator as the article prints it (tests/printed_formulas.cmake)
#include "cpu/kernel_end.h"
}  // namespace eq5_printed
}  // namespace

using namespace pt;
using namespace pt::test;

TEST_CASE("stage4 erratum 5: Eq. (5) as printed (no geometry term, no pdf) fails Lambert's formula",
          "[stage4][errata][statistical]") {
  const int size = 12;
  analytic::FloorLightScene a;
  ExpectedImage expected = floor_light_image(a, size);
  RenderSettings s = settings(size, size, 256, test_seed(3200));
  s.roulette = kRouletteThroughput;
  Scene scene = analytic::make_floor_light(a);
  const CpuKernel printed_cpu[] = {eq5_printed::cpu_kernel()};
  Film printed = render(*make_cpu_backend({"stage4 as printed", printed_cpu, {}, true}), scene, s).film;
  CHECK_FALSE(check_pixels(printed, expected).passed());
  Film right = render(*make_cpu_backend(stage4::kernels()), scene, s).film;
  CHECK(check_pixels(right, expected).passed());
}
