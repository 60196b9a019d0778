// Ray/sphere intersection in float with smallpt's walls, spheres of radius 1e5 (the bench's
// builtin:smallpt; common/kernel/intersect.glsl): the distance to the wall is right to
// the rounding of the wall's own coordinates, and a ray leaving the wall's surface does
// not find that wall again next to where it started (the speckled image of x^2 - r^2).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <random>

#include "common/scene/scene.h"
#include "cpu/kernel_prelude.h"

namespace {  // internal linkage: each test file compiles its own copy of the kernel code
namespace kernel {
#include "cpu/kernel_begin.h"
#include "common/kernel/camera.glsl"
#include "common/kernel/intersect.glsl"
#include "cpu/kernel_support.h"
}  // namespace kernel
}  // namespace

TEST_CASE("sphere precision: smallpt's floor, a sphere of radius 1e5, is hit where it is and left cleanly",
          "[intersect]") {
  pt::Scene s;
  s.add_sphere({50.0f, 1e5f, 81.6f}, 1e5f, s.add_material(pt::make_diffuse(glm::vec3(0.75f))));  // floor at y = 0
  kernel::spheres = s.spheres.data();
  kernel::params.sphere_count = 1u;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  int misses = 0, wrong = 0, self_hits = 0;
  const int rays = 20000;
  for (int i = 0; i < rays; i++) {
    // From a point of the room downwards to the floor: the distance is height / cos.
    glm::vec3 o(1.0f + 98.0f * u(rng), 1.0f + 80.0f * u(rng), 1.0f + 168.0f * u(rng));
    glm::vec3 d = glm::normalize(glm::vec3(u(rng) - 0.5f, -0.2f - u(rng), u(rng) - 0.5f));
    kernel::Hit h = kernel::intersect_scene(kernel::Ray(o, d), kernel::kInfinity);
    if (h.kind != pt::kPrimSphere) {
      misses++;
      continue;
    }
    // The exact distance to the sphere, in double.
    glm::dvec3 f = glm::dvec3(o) - glm::dvec3(50.0, 1e5, 81.6);
    double b = -glm::dot(f, glm::dvec3(d)), c = glm::dot(f, f) - 1e10;
    double exact = b + std::sqrt(b * b - c);  // from inside (c < 0): the far root
    // Right to a few steps of a float at 1e5 (1/128: the rounding of the wall's own
    // coordinates and of o - centre), taken along the ray: over the cosine to the wall.
    if (std::abs(double(h.t) - exact) > 3.0 / 128.0 / std::abs(d.y)) {
      if (wrong++ < 3) std::printf("t %.6f exact %.6f y %.3f dy %.3f\n", h.t, exact, o.y, d.y);
    }
    // Leaving the floor upwards from the hit point, with no spawn offset at all: the same
    // wall must not be met again within the room (the far side is 1e5 away).
    glm::vec3 p = o + h.t * d;
    glm::vec3 up = glm::normalize(glm::vec3(u(rng) - 0.5f, 0.02f + u(rng), u(rng) - 0.5f));
    kernel::Hit again = kernel::intersect_scene(kernel::Ray(p, up), kernel::kInfinity);
    if (again.kind == pt::kPrimSphere && again.t < 1000.0f) self_hits++;
  }
  CHECK(misses == 0);
  CHECK(wrong == 0);
  CHECK(self_hits == 0);
}
