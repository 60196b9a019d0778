// stage5_mis's pilot (common/render/mis_pilot.h, common/kernel/mis_pilot.glsl): the factor
// on the light pdf in the MIS weights, from two small independent renders that measure each
// strategy's error, on the backend under test. Its rule, the factors it chooses where the
// answer is known (the light strategy on a diffuse floor under a square light, drawn by
// solid angle; the BSDF strategy in the box furnace, where every BSDF sample finds emission),
// and that a render split into parts still adds the samples of one run bit for bit (the
// pilot does not depend on the samples a render is asked for). That the images stay
// unbiased under the factors it chooses is every closed-form test of test_stage5_images.cpp.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "common/render/mis_pilot.h"
#include "common/scene/analytic_scenes.h"
#include "common/scene/scene_loading.h"
#include "stage4_direct_indirect/kernels.h"
#include "stage5_mis/kernels.h"
#include "tests/support/test_render.h"

using namespace pt;
using namespace pt::test;

TEST_CASE("MIS pilot: the factor is the ratio of the BSDF strategy's error to the light strategy's, a power of two",
          "[stage5]") {
  CHECK(mis_scale_from({1.0, 1.0}) == 1.0f);
  CHECK(mis_scale_from({1.0, 16.0}) == 16.0f);
  CHECK(mis_scale_from({1.0, 22.0}) == 16.0f);  // log2 22 = 4.46
  CHECK(mis_scale_from({1.0, 23.0}) == 32.0f);  // 4.52
  CHECK(mis_scale_from({8.0, 1.0}) == 0.125f);
  // Within the bounds.
  CHECK(mis_scale_from({1.0, 1e9}) == kMisScaleMax);
  CHECK(mis_scale_from({1e9, 1.0}) == kMisScaleMin);
  // One strategy exact: the other gets as good as no weight; no direct light: the heuristic.
  CHECK(mis_scale_from({0.0, 3.0}) == kMisScaleMax);
  CHECK(mis_scale_from({3.0, 0.0}) == kMisScaleMin);
  CHECK(mis_scale_from({0.0, 0.0}) == 1.0f);
  CHECK(mis_scale_from({std::nan(""), 1.0}) == 1.0f);
  CHECK(mis_scale_from({1.0, INFINITY}) == 1.0f);
  CHECK(mis_summary(MisScales{16.0f, 0.25f, 32, 24}) ==
        "[mis pilot: 32x24, light pdf x16 at diffuse, x1/4 at glossy vertices]");
}

TEST_CASE("MIS pilot: the light strategy counts more under a square light, the BSDF strategy in the box furnace",
          "[stage5][statistical]") {
  auto pilot = [](const std::string& name, std::uint32_t seed) {
    RenderResult r = render_on_test_backend(stage5::kernels(), make_builtin_scene(name), settings(64, 64, 1, seed));
    INFO(name << ": " << mis_summary(r.mis));
    CHECK(r.mis.width == 32);
    CHECK(r.mis.height == 32);
    CHECK(r.mis.glossy == 1.0f);  // no glossy lobes: not measured
    return r.mis.diffuse;
  };
  // The light sample drawn by solid angle is a smooth function of its numbers there; the
  // BSDF sample finds the light or misses it (measured: errors 14 and 8500 times apart).
  CHECK(pilot("floor_large_light", test_seed(5400)) >= 4.0f);
  CHECK(pilot("floor_small_light", test_seed(5410)) >= 64.0f);
  // Every BSDF sample finds emission; the light sample picks one of 12 wall triangles by
  // area, whatever its solid angle (measured: 5 times apart).
  CHECK(pilot("furnace", test_seed(5420)) <= 0.5f);
  // The Cornell box: a small light overhead (measured: 86 times apart).
  CHECK(pilot("cornell", test_seed(5430)) >= 4.0f);
  // Glossy lobes are measured apart.
  RenderResult glossy =
      render_on_test_backend(stage5::kernels(), make_builtin_scene("cornell_glossy"), settings(48, 48, 1, test_seed(5440)));
  INFO(mis_summary(glossy.mis));
  CHECK(glossy.mis.diffuse >= 4.0f);
  CHECK(glossy.mis.glossy >= 0.25f);
  CHECK(glossy.mis.glossy <= 4.0f);
  // Other stages run no pilot.
  CHECK(render_on_test_backend(stage4::kernels(), make_builtin_scene("cornell"), settings(8, 8, 1, 1)).mis.width == 0);
}

TEST_CASE("MIS pilot: a stage5 render split at a pass end adds the samples of one run, bit for bit", "[stage5]") {
  Scene scene = make_builtin_scene("floor_large_light");
  RenderSettings all = settings(24, 16, 48, 77);
  RenderResult one = render_on_test_backend(stage5::kernels(), scene, all);
  RenderSettings first = all, second = all;
  first.spp = 32;
  second.first_sample = 32, second.spp = 16;
  RenderResult a = render_on_test_backend(stage5::kernels(), scene, first);
  RenderResult b = render_on_test_backend(stage5::kernels(), scene, second);
  // Each part ran the same pilot (the samples asked for are not among its inputs).
  CHECK(a.mis.diffuse == one.mis.diffuse);
  CHECK(b.mis.diffuse == one.mis.diffuse);
  CHECK(one.mis.diffuse != 1.0f);  // the factor is in play here
  Film merged = a.film;
  merged.merge(b.film, true);
  REQUIRE(merged.spp() == one.film.spp());
  CHECK(merged.sums() == one.film.sums());
}
