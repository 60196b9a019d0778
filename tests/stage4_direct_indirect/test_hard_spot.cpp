// A spot light with a hard edge (issue #46): Blender writes innerConeAngle ==
// outerConeAngle for Spot Blend 0, and inner >= outer means the same. The kernel's falloff
// (common/kernel/punctual_light.glsl spot_falloff, compiled as the CPU compiles it) is then
// a step at the outer angle with no division by the ramp's zero width, and the light table
// (common/scene/scene_lights.cpp) picks the light by its cone's power 2 pi (1 - cos outer) I.
#include <catch2/catch.hpp>

#include <cmath>

#include "common/scene/scene.h"
#include "cpu/kernel_prelude.h"

namespace {  // internal linkage: each test file compiles its own copy of the kernel code
namespace kernel {
#include "tests/support/light_kernel.h"
}  // namespace kernel
}  // namespace

TEST_CASE("light sampling: a hard-edged spot (inner >= outer) has weight I / d^2 up to its outer angle, 0 beyond",
          "[stage4][lights][punctual]") {
  const float outer = 0.6f, h = 2.0f;
  for (float inner : {0.6f, 0.8f}) {
    pt::Scene s;
    s.add_material(pt::make_diffuse(glm::vec3(0.5f)));
    s.point_lights.push_back(pt::make_spot_light({0.0f, h, 0.0f}, {0.0f, -1.0f, 0.0f}, {5.0f, 4.0f, 3.0f}, inner, outer));
    pt::build_light_table(s);
    kernel::bind_scene(s);
    // Angles from the axis, up to a ten-thousandth of a radian on either side of the edge.
    for (double theta : {0.0, 0.3, 0.59, 0.5999, 0.6001, 0.61, 1.0}) {
      glm::vec3 p(float(h * std::tan(theta)), 0.0f, 0.0f);
      kernel::LightSample ls = kernel::sample_point_light(0, p, 0.5f);
      double c = std::cos(theta), d2 = double(h) * h / (c * c);
      double want = theta < outer ? 5.0 / (d2 * 0.5) : 0.0;
      INFO("inner " << inner << ", theta " << theta);
      CHECK(std::isfinite(ls.weight.x));
      CHECK(ls.weight.x == Approx(want).epsilon(1e-5).margin(1e-7));
      CHECK(ls.pdf == 0.0f);
    }
    // Exactly on the edge the step is full (the cone is closed) and finite: no 0 / 0.
    pt::PointLight l = s.point_lights[0];
    CHECK(kernel::spot_falloff(l, l.cos_outer) == 1.0f);
    CHECK(kernel::spot_falloff(l, std::nextafter(l.cos_outer, -1.0f)) == 0.0f);
  }
}

TEST_CASE("light table: a hard-edged spot is picked by its cone's power 2 pi (1 - cos outer) I",
          "[stage4][lights][punctual]") {
  pt::Scene s;
  uint m = s.add_material(pt::make_diffuse(glm::vec3(0.5f)));
  s.add_triangle({-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, m);
  const float outer = std::acos(0.7f);
  s.point_lights = {pt::make_point_light({0, 1, 0}, glm::vec3(1.0f)),
                    pt::make_spot_light({0, 2, 0}, {0, -1, 0}, glm::vec3(1.0f), outer, outer),
                    pt::make_spot_light({0, 2, 0}, {0, -1, 0}, glm::vec3(1.0f), outer + 0.3f, outer)};
  pt::build_light_table(s);
  REQUIRE(s.lights.size() == 3);
  // Powers: point 4 pi; each hard spot 2 pi (1 - 0.7) = 0.6 pi, whatever its inner angle.
  CHECK(s.lights[0].pick == Approx(4.0 / 5.2).epsilon(1e-5));
  CHECK(s.lights[1].pick == Approx(0.6 / 5.2).epsilon(1e-5));
  CHECK(s.lights[2].pick == Approx(0.6 / 5.2).epsilon(1e-5));
  CHECK(s.light_power == Approx(5.2 * M_PI).epsilon(1e-5));
}
