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

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool same_hit(const kernel::Hit& a, const kernel::Hit& b) {
  return same_bits(a.t, b.t) && same_bits(a.b1, b.b1) && same_bits(a.b2, b.b2) && a.prim == b.prim && a.kind == b.kind;
}

void bind(const pt::Scene& s, const pt::Bvh& bvh) {
  kernel::triangles = s.triangles.data();
  kernel::spheres = s.spheres.data();
  kernel::triangle_soa = nullptr;
  kernel::params.triangle_count = uint(s.triangles.size());
  kernel::params.sphere_count = 0u;
  kernel::params.accel = pt::kAccelBvh;
  kernel::bvh_nodes = bvh.nodes.empty() ? nullptr : bvh.nodes.data();
  kernel::bvh_indices = bvh.indices.empty() ? nullptr : bvh.indices.data();
}

struct Tally {
  std::uint64_t rays = 0, hits = 0, mismatches = 0, ties = 0;
};

// The BVH's hit against the loop in index order, for one ray and bound t_max.
void compare(kernel::Ray ray, float t_max, Tally& tally) {
  kernel::Hit none = kernel::Hit(t_max, 0.0f, 0.0f, 0u, pt::kPrimNone);
  kernel::RayShear rs = kernel::make_ray_shear(ray.dir);
  kernel::Hit brute = kernel::nearest_triangle_in_order(ray, rs, none);
  kernel::Hit fast = kernel::nearest_triangle_bvh(ray, rs, none);
  tally.rays++;
  tally.hits += brute.kind == pt::kPrimTriangle;
  // The any-hit walk of shadow rays: a hit exactly when the brute force finds one.
  if (kernel::bvh_nodes != nullptr && kernel::occluded_bvh(ray, rs, t_max) != (brute.kind != pt::kPrimNone)) {
    tally.mismatches++;
    UNSCOPED_INFO("occluded_bvh differs from the brute force: t_max " << t_max << ", brute kind " << brute.kind);
  }
  if (!same_hit(brute, fast)) {
    tally.mismatches++;
    UNSCOPED_INFO("mismatch: brute t " << brute.t << " prim " << brute.prim << " kind " << brute.kind << "; bvh t "
                                       << fast.t << " prim " << fast.prim << " kind " << fast.kind);
  }
  if (brute.kind == pt::kPrimTriangle) {  // another triangle at the same distance: a tie
    for (uint i = 0; i < kernel::params.triangle_count; i++) {
      kernel::Hit h = kernel::hit_triangle(ray, rs, i, none);
      if (i != brute.prim && h.kind == pt::kPrimTriangle && same_bits(h.t, brute.t)) {
        tally.ties++;
        break;
      }
    }
  }
}

// Rays at a scene: towards random points of random triangles (edges and vertices too),
// along the axes (zero direction components), in random directions, and bounded at the
// brute force's own hit distance (a hit at exactly t_max is not taken).
void shoot(const pt::Scene& s, std::mt19937& rng, int count, Tally& tally) {
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  pt::Bounds b = s.bounds();
  glm::vec3 center = b.empty() ? glm::vec3(0.0f) : 0.5f * b.lo + 0.5f * b.hi;
  float size = b.empty() ? 1.0f : std::max(glm::length(b.hi - b.lo), 1e-30f);
  for (int r = 0; r < count; r++) {
    glm::vec3 origin = center + 2.0f * size * glm::vec3(unit(rng), unit(rng), unit(rng));
    glm::vec3 target = center + size * glm::vec3(unit(rng), unit(rng), unit(rng));
    if (!s.triangles.empty() && r % 4 != 3) {
      const pt::Triangle& t = s.triangles[std::size_t(rng() % s.triangles.size())];
      float b1 = 0.5f * (unit(rng) + 1.0f), b2 = 0.5f * (unit(rng) + 1.0f);
      if (r % 5 == 0) b2 = 0.0f;                   // on an edge
      if (r % 7 == 0) b1 = 0.0f, b2 = 0.0f;        // at a vertex
      if (b1 + b2 > 1.0f) b1 = 1.0f - b1, b2 = 1.0f - b2;
      target = (1.0f - b1 - b2) * t.p0 + b1 * t.p1 + b2 * t.p2;
    }
    glm::vec3 dir = target - origin;
    if (r % 6 == 5) {  // along one axis: two direction components exactly zero
      int k = int(rng() % 3);
      origin = target, origin[k] += (r % 12 < 6 ? 1.5f : -1.5f) * size;
      dir = glm::vec3(0.0f), dir[k] = r % 12 < 6 ? -1.0f : 1.0f;
    }
    if (!(glm::length(dir) > 0.0f)) continue;
    kernel::Ray ray(origin, glm::normalize(dir));
    compare(ray, kernel::kInfinity, tally);
    kernel::RayShear rs = kernel::make_ray_shear(ray.dir);
    kernel::Hit first = kernel::nearest_triangle_in_order(ray, rs, kernel::Hit(kernel::kInfinity, 0, 0, 0u, 0u));
    if (first.kind == pt::kPrimTriangle) compare(ray, first.t, tally);
  }
}

void check(const pt::Scene& s, std::mt19937& rng, int rays, const char* what, std::uint64_t min_ties = 0) {
  pt::Bvh bvh = pt::build_bvh(s.triangles);
  bind(s, bvh);
  Tally tally;
  shoot(s, rng, rays, tally);
  INFO(what << ": " << s.triangles.size() << " triangles, " << tally.rays << " rays, " << tally.hits << " hits, "
            << tally.ties << " ties");
  CHECK(tally.mismatches == 0);
  CHECK(tally.ties >= min_ties);
}

}  // namespace

TEST_CASE("bvh: the traversal finds the brute force's hit bit for bit on random scenes", "[bvh]") {
  std::mt19937 rng(777);
  for (int scene = 0; scene < 24; scene++) {
    pt::Scene s;
    const float scale = pt::test::add_random_triangles(s, rng, scene, 2 + scene * 25);
    INFO("scene " << scene << ", scale " << scale);
    check(s, rng, 600, "random");
  }
}

TEST_CASE("bvh: ties between coplanar overlapping triangles go to the lower index, as in brute force", "[bvh]") {
  // Triangles on the plane z = 0 with small integer vertices: every hit of a ray straight
  // down from an integer height has an exact t, so overlapping triangles tie. The large
  // ones come first (low indices) and sit in other leaves than the small ones they cover,
  // so the traversal often meets the higher index first.
  pt::Scene s;
  uint m = s.add_material(pt::make_diffuse(glm::vec3(0.5f)));
  for (int size = 64; size >= 1; size /= 2) {
    for (int x = 0; x < 64; x += size) {
      for (int y = 0; y < 64; y += size) {
        s.add_triangle({float(x), float(y), 0}, {float(x + size), float(y), 0}, {float(x), float(y + size), 0}, m);
      }
    }
  }
  pt::Bvh bvh = pt::build_bvh(s.triangles);
  bind(s, bvh);
  std::mt19937 rng(99);
  Tally tally;
  for (int r = 0; r < 3000; r++) {
    glm::vec3 origin(float(rng() % 256) * 0.25f, float(rng() % 256) * 0.25f, float(1 + rng() % 8));
    compare(kernel::Ray(origin, glm::vec3(0, 0, -1)), kernel::kInfinity, tally);
  }
  INFO(tally.rays << " rays, " << tally.hits << " hits, " << tally.ties << " ties");
  CHECK(tally.mismatches == 0);
  CHECK(tally.ties > 1000);
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
  std::mt19937 rng(4242);
  pt::Scene point;
  uint m = point.add_material(pt::make_diffuse(glm::vec3(0.5f)));
  for (int i = 0; i < 200; i++) point.add_triangle({1, 2, 3}, {1, 2, 3}, {1, 2, 3}, m);
  point.add_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, m);  // something to hit
  check(point, rng, 500, "at one point");

  pt::Scene one;
  one.add_material(pt::make_diffuse(glm::vec3(0.5f)));
  one.add_triangle({-1, -1, 0}, {1, -1, 0}, {0, 1, 0}, 0u);
  check(one, rng, 500, "one triangle");

  pt::Scene none;
  none.add_material(pt::make_diffuse(glm::vec3(0.5f)));
  check(none, rng, 50, "no triangles");

  pt::Scene copies;  // a grid of quads in one plane, every quad three times: ties everywhere
  pt::test::add_copied_grid(copies, 12);
  check(copies, rng, 2000, "copies in a plane", 100);

  pt::Scene spread;  // triangles from 1e-6 to 1e6 in size, at distances to match
  pt::test::add_spread_triangles(spread, rng, 600);
  check(spread, rng, 3000, "sizes 1e-6 to 1e6");
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
