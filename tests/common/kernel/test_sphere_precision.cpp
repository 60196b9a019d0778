// Ray/sphere intersection in float with smallpt's walls, spheres of radius 1e5 (the bench's
// builtin:smallpt; common/kernel/intersect.glsl): the distance to the wall is right to
// the rounding of the wall's own coordinates, and a ray leaving the wall's surface does
// not find that wall again next to where it started (the speckled image of x^2 - r^2).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <random>

#include "common/render/render.h"
#include "common/scene/scene.h"
#include "common/scene/scene_loading.h"
#include "cpu/kernel_prelude.h"

namespace {  // internal linkage: each test file compiles its own copy of the kernel code
namespace kernel {
#include "cpu/kernel_begin.h"
#include "common/kernel/camera.glsl"
#include "common/kernel/intersect.glsl"
#include "cpu/kernel_support.h"
}  // namespace kernel

// The scale of spawn_ray's offset in builtin:smallpt (its room, not its walls' spheres), as
// a render of it sets it.
float smallpt_scene_radius() {
  return pt::make_frame_params(pt::load_scene("builtin:smallpt"), pt::RenderSettings{}).scene_radius;
}
}  // namespace

TEST_CASE("sphere precision: smallpt's floor, a sphere of radius 1e5, is hit where it is and left cleanly",
          "[intersect]") {
  pt::Scene s;
  s.add_sphere({50.0f, 1e5f, 81.6f}, 1e5f, s.add_material(pt::make_diffuse(glm::vec3(0.75f))));  // floor at y = 0
  kernel::spheres = s.spheres.data();
  kernel::params.sphere_count = 1u;
  kernel::params.scene_radius = smallpt_scene_radius();
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
    // Leaving the floor upwards from the hit point as the stages do (spawn_ray: a few ulps
    // of the room's size off the surface): the same wall must not be met again within the
    // room (the far side is 1e5 away).
    glm::vec3 p = o + h.t * d;
    glm::vec3 up = glm::normalize(glm::vec3(u(rng) - 0.5f, 0.02f + u(rng), u(rng) - 0.5f));
    kernel::Ray leave = kernel::spawn_ray(p, glm::normalize(p - glm::vec3(50.0f, 1e5f, 81.6f)), up);
    kernel::Hit again = kernel::intersect_scene(leave, kernel::kInfinity);
    if (again.kind == pt::kPrimSphere && again.t < 1000.0f) self_hits++;
  }
  CHECK(misses == 0);
  CHECK(wrong == 0);
  CHECK(self_hits == 0);
}

TEST_CASE("sphere precision: a ray leaving smallpt's side wall just below the ceiling meets the ceiling there",
          "[intersect]") {
  // Where two walls of radius 1e5 meet, a ray leaving one wall a little below the other
  // must stop at that other wall, a few hundredths of a unit away. A root taken only
  // beyond the rounding of o - centre at 1e5 (1/128 per coordinate, about 0.1 units of
  // distance) let it pass through the ceiling to the light sphere above: the bright
  // streaks along builtin:smallpt's ceiling junctions (docs/results.md, the smallpt section).
  pt::Scene s;
  const uint white = s.add_material(pt::make_diffuse(glm::vec3(0.75f)));
  const glm::vec3 left_c(1e5f + 1.0f, 40.8f, 81.6f), top_c(50.0f, -1e5f + 81.6f, 81.6f);
  s.add_sphere(left_c, 1e5f, white);
  s.add_sphere(top_c, 1e5f, white);
  kernel::spheres = s.spheres.data();
  kernel::params.sphere_count = 2u;
  kernel::params.scene_radius = smallpt_scene_radius();
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  int passed_through = 0, wrong = 0, total = 0;
  for (double below : {0.5, 0.1, 0.05, 0.02, 0.01, 0.005}) {
    for (int i = 0; i < 500; i++, total++) {
      // A point on the left wall's surface (in double), `below` under the ceiling's
      // surface, left as the stages leave a surface (spawn_ray).
      double z = 10.0 + 150.0 * u(rng);
      glm::dvec3 lc(left_c), tc(top_c);
      auto ceiling_y = [&](double x) { return tc.y + std::sqrt(1e10 - (x - tc.x) * (x - tc.x) - (z - tc.z) * (z - tc.z)); };
      auto wall_x = [&](double y) { return lc.x - std::sqrt(1e10 - (y - lc.y) * (y - lc.y) - (z - lc.z) * (z - lc.z)); };
      double x = wall_x(ceiling_y(1.0) - below);
      double y = ceiling_y(x) - below;
      x = wall_x(y);
      glm::vec3 p(glm::dvec3(x, y, z));
      glm::vec3 d = glm::normalize(glm::vec3(0.05f + u(rng), 0.3f + u(rng), u(rng) - 0.5f));
      kernel::Ray ray = kernel::spawn_ray(p, glm::vec3(glm::normalize(lc - glm::dvec3(x, y, z))), d);
      glm::vec3 o = ray.origin;
      kernel::Hit h = kernel::intersect_scene(ray, kernel::kInfinity);
      // The exact distance to the ceiling from the float origin, in double. The room is
      // inside every wall's sphere (c < 0) and the ray runs outwards (b < 0): the root
      // ahead is the near one, c / (b - sqrt(b^2 - c)).
      glm::dvec3 f = glm::dvec3(o) - tc;
      double b = -glm::dot(f, glm::dvec3(d)), c = glm::dot(f, f) - 1e10;
      double exact = c / (b - std::sqrt(b * b - c));
      if (h.kind != pt::kPrimSphere || h.prim != 1u || h.t > 1000.0f) {
        if (passed_through++ < 3) std::printf("below %.3f: t %.6g prim %u, exact %.6g\n", below, h.t, h.prim, exact);
      } else if (std::abs(double(h.t) - exact) > 1e-3 * exact + 1e-4) {
        if (wrong++ < 3) std::printf("below %.3f: t %.6g exact %.6g\n", below, h.t, exact);
      }
    }
  }
  INFO(passed_through << " of " << total << " rays passed through the ceiling");
  CHECK(passed_through == 0);
  CHECK(wrong == 0);
}
