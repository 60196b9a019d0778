// One integrator source, two backends (docs/README.md), for stage6_variance_aware (beyond the
// article), run by pt_gpu_tests: the pilot chooses the same factors on the CPU and the GPU
// (powers of two, so that sums differing in their last bits choose the same), and with
// them the two images of one seed agree to float rounding, the pilot in play and through glass.
#include <catch2/catch.hpp>

#include "common/scene/scene_loading.h"
#include "stage6_variance_aware/kernels.h"
#include "tests/support/image_checks.h"
#include "tests/support/test_render.h"

using namespace pt;
using namespace pt::test;

TEST_CASE("stage6: the MIS pilot chooses the same factors on the CPU and the GPU", "[stage6][gpu]") {
  for (const char* name : {"floor_large_light", "floor_small_light", "furnace", "cornell", "cornell_glossy"}) {
    Scene scene = make_builtin_scene(name);
    RenderSettings s = settings(48, 36, 1, 26);
    RenderResult cpu = render_on("cpu", stage6::kernels(), scene, s);
    RenderResult gpu = render_on("gpu", stage6::kernels(), scene, s);
    INFO(name << ": CPU " << cpu.stage_note << ", GPU " << gpu.stage_note);
    REQUIRE(gpu.device_error.empty());
    CHECK(cpu.stage_note.find("[mis pilot: 32x24, ") == 0);
    CHECK(cpu.stage_note == gpu.stage_note);
  }
}

TEST_CASE("stage6: CPU and GPU images of the same seed agree to rounding with the pilot's factors and through glass",
          "[stage6][gpu]") {
  // The Cornell box: the pilot's factor on the light pdf is far from 1 (x16 or so); the glass
  // slab: refractions, eta_scale and the square-root roulette; the box furnace: the roulette
  // after emission at every bounce, may_find_emission on every ended path.
  for (std::uint32_t roulette : {kRouletteThroughput, kRouletteFixed}) {
    for (const char* name : {"cornell", "glass_slab", "furnace"}) {
      Scene scene = make_builtin_scene(name);
      RenderSettings s = settings(48, 36, 4, 28);
      s.roulette = roulette;
      RenderResult cpu = render_on("cpu", stage6::kernels(), scene, s);
      RenderResult gpu = render_on("gpu", stage6::kernels(), scene, s);
      INFO(name << (roulette == kRouletteFixed ? ", --rr fixed: " : ", --rr throughput: ") << cpu.stage_note);
      REQUIRE(gpu.device_error.empty());
      CHECK(cpu.stage_note == gpu.stage_note);
      CHECK(agreeing_fraction(cpu.film, gpu.film) >= 0.999);
    }
  }
}
