// The BVH traversal (common/kernel/bvh.glsl, compiled here as C++ as the CPU kernels
// compile it; the acceleration structure the article's GPU section lacks) finds exactly the
// brute force's hit: t, barycentrics and triangle bit for bit, the lower index on a tie, on
// random scenes with copies, zero-area and coplanar triangles, all triangles at one point,
// sizes from 1e-6 to 1e6, one triangle and none; and the box test never misses.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <random>

#include "common/scene/bvh.h"
#include "common/scene/scene.h"
#include "tests/support/random_scenes.h"
#include "cpu/kernel_prelude.h"

namespace {  // internal linkage: each test file compiles its own copy of the kernel code
namespace kernel {
#include "cpu/kernel_begin.h"
#include "common/kernel/camera.glsl"
#include "common/kernel/intersect.glsl"
#include "cpu/kernel_support.h"
}  // namespace kernel

#include "tests/support/bvh_walk_check.h"

}  // namespace

TEST_CASE("bvh: the traversal finds the brute force's hit bit for bit on random scenes", "[bvh]") {
  check_random_scenes();
}

TEST_CASE("bvh: ties between coplanar overlapping triangles go to the lower index, as in brute force", "[bvh]") {
  pt::Scene s = coplanar_overlaps();
  check_coplanar_ties(s);
  // And through hit_triangle_tie() directly: the lower index at the same t replaces a hit.
  kernel::Ray down(glm::vec3(0.25f, 0.25f, 2.0f), glm::vec3(0, 0, -1));
  kernel::RayShear rs = kernel::make_ray_shear(down.dir);
  const uint last = uint(s.triangles.size() - 64 * 64);  // the smallest triangle at the corner
  kernel::Hit high = kernel::hit_triangle(down, rs, last, kernel::Hit(kernel::kInfinity, 0, 0, 0u, 0u));
  REQUIRE(high.kind == pt::kPrimTriangle);
  CHECK(kernel::hit_triangle(down, rs, 0u, high).prim == last);  // the plain test keeps the first found
  kernel::Hit low = kernel::hit_triangle_tie(down, rs, 0u, high);
  CHECK(low.prim == 0u);
  CHECK(same_bits(low.t, high.t));
  CHECK(kernel::hit_triangle_tie(down, rs, last, low).prim == 0u);  // the higher index does not
}

TEST_CASE("bvh: degenerate scenes: one point, one triangle, none, a plane of copies, 1e-6 to 1e6", "[bvh]") {
  check_degenerate_scenes();
}

TEST_CASE("bvh: the box test never says no for a ray through the box, nor for a NaN ray", "[bvh]") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  int missed = 0;
  for (int i = 0; i < 20000; i++) {
    float scale = std::pow(10.0f, float(int(rng() % 13) - 6));
    glm::vec3 lo = scale * glm::vec3(unit(rng), unit(rng), unit(rng));
    glm::vec3 hi = lo + scale * (i % 3 == 0 ? glm::vec3(0.0f) : glm::vec3(1.0f + unit(rng), 1.0f + unit(rng), 0.0f));
    glm::vec3 p = glm::mix(lo, hi, glm::vec3(0.5f * (unit(rng) + 1.0f), 0.5f * (unit(rng) + 1.0f), 1.0f));
    glm::vec3 origin = p + 3.0f * scale * glm::vec3(unit(rng), unit(rng), unit(rng));
    if (i % 4 == 1) origin = glm::vec3(p.x, p.y, p.z + 2.0f * scale);  // along -z exactly
    glm::vec3 dir = glm::normalize(p - origin);
    float t = glm::length(p - origin);
    missed += !kernel::hit_box(kernel::Ray(origin, dir), kernel::inverse_direction(dir), lo, hi, t);
  }
  CHECK(missed == 0);
  float nan = std::nanf("");
  CHECK(kernel::hit_box(kernel::Ray(glm::vec3(0, 0, 5), glm::vec3(nan, 0, -1)),
                        kernel::inverse_direction(glm::vec3(nan, 0, -1)), glm::vec3(-1), glm::vec3(1), 100.0f));
  // A box behind the ray, and one beyond t_max, are missed.
  glm::vec3 down(0, 0, -1);
  CHECK_FALSE(kernel::hit_box(kernel::Ray(glm::vec3(0, 0, -5), down), kernel::inverse_direction(down), glm::vec3(-1),
                              glm::vec3(1), 100.0f));
  CHECK_FALSE(kernel::hit_box(kernel::Ray(glm::vec3(0, 0, 50), down), kernel::inverse_direction(down), glm::vec3(-1),
                              glm::vec3(1), 10.0f));
}
