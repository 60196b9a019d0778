// The CPU's wide BVH (cpu/wide_bvh.h: the binary tree of the step after the article's GPU
// section collapsed to 8 children and leaf blocks, walked on SIMD lanes) finds exactly the
// brute force's hit: t, barycentrics and triangle bit for bit, the lower index on a tie, on
// random scenes with copies, coplanar overlaps, slivers, zero-area triangles, all triangles
// at one point, sizes from 1e-6 to 1e6, one triangle, none and NaN rays; its any-hit walk
// agrees with the nearest hit within t_max; on 4 lanes and on 8, for leaves of 4 and of 8.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <random>

#include "common/scene/bvh.h"
#include "common/scene/scene.h"
#include "tests/support/random_scenes.h"
#include "cpu/kernel_prelude.h"
#include "cpu/wide_bvh.h"

namespace {  // internal linkage: each test file compiles its own copy of the kernel code
namespace kernel {
#include "cpu/kernel_begin.h"
#include "common/kernel/camera.glsl"
#include "common/kernel/intersect.glsl"
#include "cpu/kernel_support.h"
}  // namespace kernel

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

struct Tally {
  std::uint64_t rays = 0, hits = 0, mismatches = 0, ties = 0;
};

// The wide walk (on `lanes` lanes) against the loop in index order, for one ray and t_max.
void compare(const pt::WideBvh& wide, kernel::Ray ray, float t_max, int lanes, Tally& tally) {
  kernel::Hit none = kernel::Hit(t_max, 0.0f, 0.0f, 0u, pt::kPrimNone);
  kernel::RayShear rs = kernel::make_ray_shear(ray.dir);
  kernel::Hit brute = kernel::nearest_triangle_in_order(ray, rs, none);
  pt::WideHit fast = pt::wide_bvh_nearest(wide, kernel::wide_ray(ray, rs), pt::WideHit{t_max, 0.0f, 0.0f, -1}, lanes);
  const bool occluded = pt::wide_bvh_occluded(wide, kernel::wide_ray(ray, rs), t_max, lanes);
  tally.rays++;
  tally.hits += brute.kind == pt::kPrimTriangle;
  const bool same = brute.kind == pt::kPrimTriangle
                        ? fast.prim == std::int32_t(brute.prim) && same_bits(fast.t, brute.t) &&
                              same_bits(fast.b1, brute.b1) && same_bits(fast.b2, brute.b2)
                        : fast.prim == -1 && same_bits(fast.t, t_max);
  if (!same || occluded != (brute.kind == pt::kPrimTriangle)) {
    tally.mismatches++;
    UNSCOPED_INFO(lanes << " lanes: brute t " << std::hexfloat << brute.t << " b " << brute.b1 << " " << brute.b2
                        << " prim " << brute.prim << " kind " << brute.kind << "; wide t " << fast.t << " b "
                        << fast.b1 << " " << fast.b2 << " prim " << fast.prim << std::defaultfloat << "; occluded "
                        << occluded);
  }
  if (brute.kind == pt::kPrimTriangle) {  // another triangle at the same distance: a tie
    for (uint i = 0; i < kernel::params.triangle_count; i++) {
      kernel::Hit h = kernel::hit_triangle(ray, rs, i, none);
      if (i != brute.prim && h.kind == pt::kPrimTriangle && same_bits(h.t, brute.t)) {
        tally.ties++;
        break;
      }
    }
    // A hit already held at the same t with a higher index gives way to the lower one.
    kernel::Hit held = kernel::hit_triangle(ray, rs, brute.prim, none);
    pt::WideHit in{held.t, held.b1, held.b2, std::int32_t(brute.prim)};
    pt::WideHit again = pt::wide_bvh_nearest(wide, kernel::wide_ray(ray, rs), in, lanes);
    if (again.prim != std::int32_t(brute.prim) || !same_bits(again.t, brute.t)) tally.mismatches++;
  }
}

// Rays at a scene as test_bvh_traversal.cpp shoots them: at points of random triangles
// (edges and vertices too), along the axes, in random directions, bounded at infinity and
// at the brute force's own hit distance; some with a NaN direction.
void check(const pt::Scene& s, std::mt19937& rng, int count, const char* what, std::uint64_t min_ties = 0) {
  pt::Bvh bvh = pt::build_bvh(s.triangles);
  kernel::triangles = s.triangles.data();
  kernel::params.triangle_count = uint(s.triangles.size());
  pt::Bounds b = s.bounds();
  glm::vec3 center = b.empty() ? glm::vec3(0.0f) : 0.5f * b.lo + 0.5f * b.hi;
  float size = b.empty() ? 1.0f : std::max(glm::length(b.hi - b.lo), 1e-30f);
  for (unsigned leaf_max : {4u, 8u}) {
    const pt::WideBvh wide = pt::build_wide_bvh(bvh, s.triangles, leaf_max);
    REQUIRE(wide.nodes.empty() == s.triangles.empty());
    Tally tally;
    for (int r = 0; r < count; r++) {
      glm::vec3 origin, dir;
      pt::test::random_test_ray(s, rng, r, center, size, origin, dir);
      if (!(glm::length(dir) > 0.0f)) continue;
      dir = glm::normalize(dir);
      if (r % 97 == 13) dir.y = std::nanf("");  // a NaN ray: no hit, by either search
      for (int lanes : {4, 8}) {
        kernel::Ray ray(origin, dir);
        compare(wide, ray, kernel::kInfinity, lanes, tally);
        kernel::RayShear rs = kernel::make_ray_shear(ray.dir);
        kernel::Hit first = kernel::nearest_triangle_in_order(ray, rs, kernel::Hit(kernel::kInfinity, 0, 0, 0u, 0u));
        if (first.kind == pt::kPrimTriangle) compare(wide, ray, first.t, lanes, tally);  // at t_max: not taken
      }
    }
    INFO(what << ", leaves of " << leaf_max << ": " << s.triangles.size() << " triangles, " << wide.nodes.size()
              << " nodes, " << tally.rays << " rays, " << tally.hits << " hits, " << tally.ties << " ties");
    CHECK(tally.mismatches == 0);
    CHECK(tally.ties >= min_ties);
  }
}

}  // namespace

TEST_CASE("wide bvh: the CPU's SIMD walk finds the brute force's hit bit for bit on random scenes", "[bvh]") {
  std::mt19937 rng(2024);
  for (int scene = 0; scene < 20; scene++) {
    pt::Scene s;
    const float scale = pt::test::add_random_triangles(s, rng, scene, 1 + scene * 37);
    INFO("scene " << scene << ", scale " << scale);
    check(s, rng, 400, "random");
  }
}

TEST_CASE("wide bvh: coplanar overlaps, copies, one point, one triangle, none, 1e-6 to 1e6", "[bvh]") {
  std::mt19937 rng(31337);
  pt::Scene plane;  // overlapping triangles on z = 0, the large ones first: ties everywhere
  uint m = plane.add_material(pt::make_diffuse(glm::vec3(0.5f)));
  for (int size = 32; size >= 1; size /= 2) {
    for (int x = 0; x < 32; x += size) {
      for (int y = 0; y < 32; y += size) {
        plane.add_triangle({float(x), float(y), 0}, {float(x + size), float(y), 0}, {float(x), float(y + size), 0}, m);
      }
    }
  }
  check(plane, rng, 1500, "coplanar overlaps", 100);
  {
    const pt::Bvh bvh = pt::build_bvh(plane.triangles);
    const pt::WideBvh wide = pt::build_wide_bvh(bvh, plane.triangles);
    Tally tally;  // straight down from integer heights: exact distances, so overlaps tie
    for (int r = 0; r < 2000; r++) {
      glm::vec3 origin(float(rng() % 128) * 0.25f, float(rng() % 128) * 0.25f, float(1 + rng() % 8));
      compare(wide, kernel::Ray(origin, glm::vec3(0, 0, -1)), kernel::kInfinity, r % 2 ? 4 : 8, tally);
    }
    INFO(tally.rays << " rays straight down, " << tally.ties << " ties");
    CHECK(tally.mismatches == 0);
    CHECK(tally.ties > 1000);
  }

  for (const pt::test::DegenerateScene& d : pt::test::degenerate_scenes(rng)) check(d.scene, rng, d.rays, d.name, d.min_ties);
}

TEST_CASE("wide bvh: every triangle lands in exactly one leaf block, under boxes of the binary tree", "[bvh]") {
  std::mt19937 rng(8);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  pt::Scene s;
  s.add_material(pt::make_diffuse(glm::vec3(0.5f)));
  for (int i = 0; i < 3000; i++) {
    glm::vec3 c = 10.0f * glm::vec3(unit(rng), unit(rng), unit(rng));
    s.add_triangle(c, c + 0.3f * glm::vec3(unit(rng), unit(rng), unit(rng)), c + 0.3f * glm::vec3(unit(rng), unit(rng), unit(rng)), 0u);
  }
  const pt::Bvh bvh = pt::build_bvh(s.triangles);
  for (unsigned leaf_max : {4u, 8u}) {
    const pt::WideBvh wide = pt::build_wide_bvh(bvh, s.triangles, leaf_max);
    std::vector<int> seen(s.triangles.size(), 0);
    for (const pt::WideBlock& b : wide.blocks) {
      for (int i = 0; i < pt::kWideWidth; i++) {
        if (b.index[i] >= 0) seen[std::size_t(b.index[i])]++;
      }
    }
    CHECK(std::count(seen.begin(), seen.end(), 1) == std::ptrdiff_t(s.triangles.size()));
    CHECK(wide.nodes.size() < bvh.nodes.size() / 4);  // a wide tree: far fewer nodes
  }
}
