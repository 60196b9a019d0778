// One integrator source, two backends (DESIGN.md): the CPU and GPU images of the same
// scene, seed and spp must agree to float rounding, not only statistically.
#include <catch2/catch.hpp>

#include <cmath>

#include "common/scene_loading.h"
#include "stage1_raycast/kernels.h"
#include "stage2_montecarlo/kernels.h"
#include "tests/support/test_render.h"

using namespace pt;
using namespace pt::test;

namespace {

// Fraction of pixels whose every channel agrees within a relative 1e-5 (or 1e-6 absolute).
double agreeing_fraction(const Film& a, const Film& b) {
  int agree = 0;
  for (int y = 0; y < a.height(); y++) {
    for (int x = 0; x < a.width(); x++) {
      glm::dvec3 u = a.mean(x, y), v = b.mean(x, y);
      bool same = true;
      for (int c = 0; c < 3; c++) same = same && std::abs(u[c] - v[c]) <= 1e-6 + 1e-5 * std::abs(u[c]);
      agree += same;
    }
  }
  return double(agree) / (double(a.width()) * a.height());
}

}  // namespace

TEST_CASE("stage1: CPU and GPU images of the same seed agree to rounding", "[stage1][gpu]") {
  for (const char* name : {"cornell", "sphere", "quad"}) {
    Scene scene = make_builtin_scene(name);
    RenderSettings s = settings(96, 72, 8, 21);
    RenderResult cpu = render_on("cpu", stage1::kernels(), scene, s);
    RenderResult gpu = render_on("gpu", stage1::kernels(), scene, s);
    INFO("scene " << name);
    CHECK(agreeing_fraction(cpu.film, gpu.film) >= 0.999);
  }
}

TEST_CASE("stage2: CPU and GPU images of the same seed agree to rounding", "[stage2][gpu]") {
  for (const char* name : {"cornell", "furnace", "glass_slab"}) {
    Scene scene = make_builtin_scene(name);
    RenderSettings s = settings(48, 36, 4, 22);
    RenderResult cpu = render_on("cpu", stage2::kernels(), scene, s);
    RenderResult gpu = render_on("gpu", stage2::kernels(), scene, s);
    INFO("scene " << name);
    CHECK(agreeing_fraction(cpu.film, gpu.film) >= 0.999);
  }
}
