// The CPU's block test of the spheres (cpu/sphere_lanes.h, the structure-of-arrays fast path
// of Eq. 2's raycasting for spheres) finds the same hits as the plain loop over
// hit_sphere(), bit for bit: same t and sphere, and the same answer for shadow rays. Scenes
// of random spheres (radii from 1e-3 to 1e5, smallpt's walls, centres far from the world
// origin, copies of a sphere, whose hits tie, counts that are not a multiple of the lane
// count) and rays from outside, from inside, and from points on a sphere (where a path's
// next ray starts).
#include <catch2/catch.hpp>

#include <cstring>
#include <random>

#include "common/scene/scene_loading.h"
#include "common/scene/scene.h"
#include "cpu/kernel_prelude.h"
#include "cpu/sphere_soa.h"

namespace {  // internal linkage: each test file compiles its own copy of the kernel code
namespace kernel {
#include "cpu/kernel_begin.h"
#include "common/kernel/camera.glsl"
#include "common/kernel/intersect.glsl"
#include "cpu/kernel_support.h"
}  // namespace kernel

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

struct Counts {
  std::uint64_t rays = 0, hits = 0, blocked = 0;
};

// Every ray of `rays` against `scene`'s spheres, by the loop and by the lanes.
template <class RayMaker>
void check_same_hits(const pt::Scene& scene, int rays, RayMaker make_ray, Counts& counts) {
  pt::SphereSoa soa(scene.spheres);
  kernel::triangles = scene.triangles.data();
  kernel::spheres = scene.spheres.data();
  kernel::params.triangle_count = uint(scene.triangles.size());
  kernel::params.sphere_count = uint(scene.spheres.size());
  for (int r = 0; r < rays; r++) {
    float t_max = kernel::kInfinity;
    kernel::Ray ray = make_ray(r, t_max);
    kernel::sphere_soa = nullptr;
    const kernel::Hit plain = kernel::intersect_scene(ray, t_max);
    const bool plain_blocked = kernel::occluded_scene(ray, t_max);
    kernel::sphere_soa = soa.data.data();
    kernel::sphere_soa_stride = soa.stride;
    kernel::sphere_soa_count = soa.count;
    const kernel::Hit lanes = kernel::intersect_scene(ray, t_max);
    const bool lanes_blocked = kernel::occluded_scene(ray, t_max);
    kernel::sphere_soa = nullptr;
    INFO("ray " << r << " from (" << ray.origin.x << ", " << ray.origin.y << ", " << ray.origin.z << ")");
    REQUIRE(plain.kind == lanes.kind);
    REQUIRE(plain.prim == lanes.prim);
    REQUIRE(same_bits(plain.t, lanes.t));
    REQUIRE(plain_blocked == lanes_blocked);
    counts.rays++;
    counts.hits += plain.kind != kernel::kPrimNone;
    counts.blocked += plain_blocked;
  }
}

}  // namespace

TEST_CASE("intersect: the CPU's block test of spheres finds the same hits as the plain loop, bit for bit",
          "[intersect]") {
  std::mt19937 rng(4242);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::uniform_int_distribution<int> exponent(-3, 5);
  Counts counts;
  for (int scene_index = 0; scene_index < 30; scene_index++) {
    pt::Scene s;
    const uint m = s.add_material(pt::make_diffuse(glm::vec3(0.5f)));
    const float scale = std::pow(10.0f, float(exponent(rng)));
    const glm::vec3 offset = glm::vec3(unit(rng), unit(rng), unit(rng)) * scale * float(scene_index % 3 * 1000);
    const int count = 1 + scene_index % 19;  // 1 ... 19: every remainder of 4 and 8 lanes
    for (int i = 0; i < count; i++) {
      const float radius = scale * std::pow(10.0f, 0.5f * unit(rng) - (i % 4 == 1 ? 2.0f : 0.0f));
      glm::vec3 center = offset + 2.0f * scale * glm::vec3(unit(rng), unit(rng), unit(rng));
      if (i % 6 == 5) center = s.spheres[std::size_t(i) / 2].center;  // a copy: ties
      s.add_sphere(center, i % 6 == 5 ? s.spheres[std::size_t(i) / 2].radius : radius, m);
    }
    check_same_hits(s, 1500, [&](int r, float& t_max) {
      const pt::Sphere& target = s.spheres[std::size_t(rng()) % s.spheres.size()];
      glm::vec3 aim = target.center + target.radius * glm::vec3(unit(rng), unit(rng), unit(rng));
      glm::vec3 origin = offset + 4.0f * scale * glm::vec3(unit(rng), unit(rng), unit(rng));
      if (r % 4 == 1) {  // from a point on a sphere, as a path's next ray starts
        const pt::Sphere& from = s.spheres[std::size_t(rng()) % s.spheres.size()];
        glm::vec3 d = glm::vec3(unit(rng), unit(rng), unit(rng));
        if (glm::length(d) > 0.0f) origin = from.center + from.radius * glm::normalize(d);
      }
      if (r % 4 == 2) origin = target.center;  // from inside
      if (glm::length(aim - origin) == 0.0f) aim += glm::vec3(scale);
      if (r % 3 == 0) t_max = 3.0f * scale * (unit(rng) + 1.0f);
      return kernel::Ray(origin, glm::normalize(aim - origin));
    }, counts);
  }
  // smallpt's scene: walls of radius 1e5, rays from the room and from its walls.
  const pt::Scene smallpt = pt::make_builtin_scene("smallpt");
  check_same_hits(smallpt, 20000, [&](int r, float& t_max) {
    glm::vec3 origin(50.0f + 45.0f * unit(rng), 40.0f + 38.0f * unit(rng), 85.0f + 80.0f * unit(rng));
    if (r % 2 == 1) origin.x = r % 4 == 1 ? 1.0f : 99.0f;  // on a side wall
    if (r % 5 == 0) t_max = 50.0f * (unit(rng) + 1.0f);
    glm::vec3 d(unit(rng), unit(rng), unit(rng));
    if (glm::length(d) == 0.0f) d = glm::vec3(0.0f, 1.0f, 0.0f);
    return kernel::Ray(origin, glm::normalize(d));
  }, counts);
  INFO(counts.rays << " rays, " << counts.hits << " hits, " << counts.blocked << " blocked");
  CHECK(counts.hits > counts.rays / 2);  // the rays test hits, not only misses
  CHECK(counts.blocked < counts.rays);   // and some shadow rays pass
}
