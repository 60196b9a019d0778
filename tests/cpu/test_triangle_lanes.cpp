// The CPU's block test of the nearest-hit search (cpu/triangle_lanes.h, the
// structure-of-arrays fast path of Eq. 2's raycasting) finds the same hits as the plain loop
// over hit_triangle(), bit for bit: same t, barycentrics, triangle. Scenes of random
// triangles (sizes and positions over many orders of magnitude, slivers, shared edges, empty
// triangles, copies of a triangle, whose hits tie, counts that are not a multiple of the
// lane count) and rays aimed at them.
#include <catch2/catch.hpp>

#include <cstring>
#include <random>

#include "common/scene/scene.h"
#include "cpu/kernel_prelude.h"
#include "cpu/triangle_soa.h"

namespace {  // internal linkage: each test file compiles its own copy of the kernel code
namespace kernel {
#include "cpu/kernel_begin.h"
#include "common/kernel/camera.glsl"
#include "common/kernel/intersect.glsl"
#include "cpu/kernel_support.h"
}  // namespace kernel

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST_CASE("intersect: the CPU's block test finds the same hits as the plain loop, bit for bit", "[intersect]") {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::uniform_int_distribution<int> exponent(-6, 6);
  std::uint64_t rays = 0, hits = 0;
  for (int scene_index = 0; scene_index < 40; scene_index++) {
    pt::Scene s;
    uint m = s.add_material(pt::make_diffuse(glm::vec3(0.5f)));
    const float scale = std::pow(10.0f, float(exponent(rng)));
    const glm::vec3 offset = glm::vec3(unit(rng), unit(rng), unit(rng)) * scale * float(scene_index % 3 * 100);
    const int count = 1 + scene_index * 3;  // 1 ... 118: every remainder of the block size
    auto point = [&] { return offset + scale * glm::vec3(unit(rng), unit(rng), unit(rng)); };
    for (int i = 0; i < count; i++) {
      glm::vec3 a = point(), b = point(), c = point();
      if (i % 7 == 3) c = a + 1e-4f * (b - a);  // a sliver
      if (i % 11 == 5 && i > 0) {               // shares an edge with the last triangle
        const pt::Triangle& last = s.triangles.back();
        a = last.p1, b = last.p0;
      }
      if (i % 13 == 9) {  // the same as an earlier triangle: hits at equal distances
        const pt::Triangle& earlier = s.triangles[std::size_t(i) / 2];
        a = earlier.p0, b = earlier.p1, c = earlier.p2;
      }
      s.add_triangle(a, b, c, m);
    }
    pt::TriangleSoa soa(s.triangles);
    kernel::triangles = s.triangles.data();
    kernel::spheres = s.spheres.data();
    kernel::params.triangle_count = uint(s.triangles.size());
    for (int r = 0; r < 2000; r++) {
      // From a random point towards a random point of a random triangle (or its edge).
      const pt::Triangle& target = s.triangles[std::size_t(rng() % s.triangles.size())];
      float b1 = 0.5f * (unit(rng) + 1.0f), b2 = 0.5f * (unit(rng) + 1.0f);
      if (b1 + b2 > 1.0f) b1 = 1.0f - b1, b2 = 1.0f - b2;
      if (r % 5 == 0) b2 = 1.0f - b1;  // on an edge
      glm::vec3 aim = (1.0f - b1 - b2) * target.p0 + b1 * target.p1 + b2 * target.p2;
      glm::vec3 origin = offset + 3.0f * scale * glm::vec3(unit(rng), unit(rng), unit(rng));
      if (glm::length(aim - origin) == 0.0f) continue;
      kernel::Ray ray(origin, glm::normalize(aim - origin));
      const float t_max = r % 3 == 0 ? kernel::kInfinity : 2.0f * scale * (unit(rng) + 1.0f);
      kernel::triangle_soa = nullptr;
      kernel::Hit plain = kernel::intersect_scene(ray, t_max);
      kernel::triangle_soa = soa.data.data();
      kernel::triangle_soa_stride = soa.stride;
      kernel::Hit blocked = kernel::intersect_scene(ray, t_max);
      kernel::triangle_soa = nullptr;
      INFO("scene " << scene_index << ", ray " << r);
      REQUIRE(plain.kind == blocked.kind);
      REQUIRE(plain.prim == blocked.prim);
      REQUIRE(same_bits(plain.t, blocked.t));
      REQUIRE(same_bits(plain.b1, blocked.b1));
      REQUIRE(same_bits(plain.b2, blocked.b2));
      rays++;
      hits += plain.kind != kernel::kPrimNone;
    }
  }
  INFO(rays << " rays, " << hits << " hits");
  CHECK(hits > rays / 2);  // the rays test hits, not only misses
}
