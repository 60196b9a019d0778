// Erratum 2: Eq. (4) as printed is Eq. (3) again, with no pdf. Built from stage3's own
// integrator (printed/stage3_eq4.glsl, written by tests/printed_formulas.cmake), it fails the furnace test, which f cos / pdf passes.
#include <catch2/catch.hpp>

#include <cmath>

#include "cpu/cpu_backend.h"
#include "common/scene/analytic_scenes.h"
#include "cpu/kernel_prelude.h"
#include "stage3_importance/kernels.h"
#include "tests/support/image_checks.h"
#include "tests/support/test_render.h"

namespace {  // internal linkage: each namespace below compiles its own copy
namespace eq4_printed {
#include "cpu/kernel_begin.h"
#include "printed/stage3_eq4.glsl"  // the integrator as the article prints it (tests/printed_formulas.cmake)
#include "cpu/kernel_end.h"
}  // namespace eq4_printed
}  // namespace

using namespace pt;
using namespace pt::test;

TEST_CASE("stage3 erratum 2: Eq. (4) as printed (no pdf) fails the furnace test; f cos / pdf passes",
          "[stage3][errata][statistical]") {
  analytic::FurnaceScene f;  // albedo 0.5, Le 1: 2
  Scene scene = analytic::make_furnace(f);
  RenderSettings s = settings(8, 8, 256, test_seed(3100));
  s.roulette = kRouletteThroughput;
  ExpectedImage want(64, glm::dvec3(2.0));
  const CpuKernel printed_cpu[] = {eq4_printed::cpu_kernel()};
  Film printed = render(*make_cpu_backend({"stage3 as printed", printed_cpu, {}}), scene, s).film;
  CHECK_FALSE(check_pixels(printed, want).passed());
  Film right = render(*make_cpu_backend(stage3::kernels()), scene, s).film;
  CHECK(check_pixels(right, want).passed());
}
