// The BVH builder (common/scene/bvh.cpp, the acceleration structure that the article's GPU
// section still lacks): on random and degenerate triangle sets, every primitive sits in
// exactly one leaf, every child's box inside its parent's, every triangle inside its leaf's
// box, and the tree is no deeper than the traversal's stack.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "common/scene/bvh.h"
#include "common/scene/scene.h"

using namespace pt;

namespace {

bool inside(glm::vec3 p, const BvhNode& n) {
  return p.x >= n.lo.x && p.y >= n.lo.y && p.z >= n.lo.z && p.x <= n.hi.x && p.y <= n.hi.y && p.z <= n.hi.z;
}

// Checks the invariants of a BVH over `tris`, walking it from the root.
void check_invariants(const std::vector<Triangle>& tris, const Bvh& bvh) {
  if (tris.empty()) {
    CHECK(bvh.nodes.empty());
    CHECK(bvh.indices.empty());
    return;
  }
  REQUIRE(!bvh.nodes.empty());
  REQUIRE(bvh.indices.size() == tris.size());
  CHECK(bvh.stats.nodes == bvh.nodes.size());
  CHECK(bvh.stats.depth < kBvhStackSize);
  std::vector<int> seen(tris.size(), 0);
  std::vector<int> visits(bvh.nodes.size(), 0);
  struct Item {
    uint node;
    unsigned depth;
  };
  std::vector<Item> stack{{0u, 0u}};
  unsigned deepest = 0;
  bool boxes_nested = true, triangles_inside = true, leaves_small = true;
  while (!stack.empty()) {
    Item item = stack.back();
    stack.pop_back();
    REQUIRE(item.node < bvh.nodes.size());
    visits[item.node]++;
    deepest = std::max(deepest, item.depth);
    const BvhNode& n = bvh.nodes[item.node];
    if (n.count == 0u) {
      REQUIRE(n.first_or_left + 1u < bvh.nodes.size());
      for (uint c = n.first_or_left; c <= n.first_or_left + 1u; c++) {
        boxes_nested = boxes_nested && inside(bvh.nodes[c].lo, n) && inside(bvh.nodes[c].hi, n);
        stack.push_back({c, item.depth + 1});
      }
      continue;
    }
    leaves_small = leaves_small && n.count <= kBvhMaxLeaf;
    REQUIRE(std::size_t(n.first_or_left) + n.count <= bvh.indices.size());
    for (uint i = n.first_or_left; i < n.first_or_left + n.count; i++) {
      uint t = bvh.indices[i];
      REQUIRE(t < tris.size());
      seen[t]++;
      triangles_inside = triangles_inside && inside(tris[t].p0, n) && inside(tris[t].p1, n) && inside(tris[t].p2, n);
    }
  }
  CHECK(boxes_nested);
  CHECK(triangles_inside);
  CHECK(leaves_small);
  CHECK(deepest == bvh.stats.depth);
  CHECK(std::count(seen.begin(), seen.end(), 1) == std::ptrdiff_t(tris.size()));  // each exactly once
  CHECK(std::count(visits.begin(), visits.end(), 1) == std::ptrdiff_t(bvh.nodes.size()));  // a tree
}

}  // namespace

TEST_CASE("bvh: every triangle in exactly one leaf, boxes nested, triangles inside their leaves", "[bvh]") {
  std::mt19937 rng(2024);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::uniform_int_distribution<int> exponent(-6, 6);
  for (int scene = 0; scene < 30; scene++) {
    const float scale = std::pow(10.0f, float(exponent(rng)));
    const glm::vec3 offset = scale * float(scene % 4) * 10.0f * glm::vec3(unit(rng), unit(rng), unit(rng));
    std::vector<Triangle> tris;
    const int count = scene * scene * 3;  // 0 ... 2523
    for (int i = 0; i < count; i++) {
      auto p = [&] { return offset + scale * glm::vec3(unit(rng), unit(rng), unit(rng)); };
      Triangle t{p(), 0u, p(), kNoLight, p(), 0u};
      if (i % 5 == 1) t.p2 = t.p1;                              // zero area
      if (i % 7 == 2 && i > 0) t = tris[std::size_t(i) / 2];    // a duplicate
      if (i % 9 == 3) t.p0.z = t.p1.z = t.p2.z = offset.z;      // coplanar with others
      tris.push_back(t);
    }
    INFO("scene " << scene << ", " << count << " triangles");
    check_invariants(tris, build_bvh(tris));
  }
}

TEST_CASE("bvh: degenerate sets: one point, one triangle, none, copies, a wide range of sizes", "[bvh]") {
  const glm::vec3 p(0.3f, -2.0f, 7.0f);
  std::vector<Triangle> point(1000, Triangle{p, 0u, p, kNoLight, p, 0u});
  Bvh at_point = build_bvh(point);
  check_invariants(point, at_point);
  CHECK(at_point.nodes.size() > 1);  // still split into small leaves, by the median

  std::vector<Triangle> copies(777, Triangle{{0, 0, 0}, 0u, {1, 0, 0}, kNoLight, {0, 1, 0}, 0u});
  check_invariants(copies, build_bvh(copies));

  std::vector<Triangle> one{Triangle{{0, 0, 0}, 0u, {1, 0, 0}, kNoLight, {0, 1, 0}, 0u}};
  Bvh single = build_bvh(one);
  check_invariants(one, single);
  CHECK(single.nodes.size() == 1);

  check_invariants({}, build_bvh({}));

  // Sizes and positions from 1e-6 to 1e6, in one scene: spaced geometrically, the SAH
  // would split one triangle off at a time; the depth limit keeps the tree shallow.
  std::vector<Triangle> spread;
  for (int i = 0; i < 4000; i++) {
    float s = std::pow(10.0f, -6.0f + 12.0f * float(i) / 4000.0f);
    spread.push_back(Triangle{{s, s, s}, 0u, {s * 1.01f, s, s}, kNoLight, {s, s * 1.01f, s}, 0u});
  }
  check_invariants(spread, build_bvh(spread));
}

TEST_CASE("bvh: the summary tag gives nodes, build time and bytes per triangle", "[bvh]") {
  std::vector<Triangle> tris;
  for (int i = 0; i < 100; i++) {
    float x = float(i);
    tris.push_back(Triangle{{x, 0, 0}, 0u, {x + 1, 0, 0}, kNoLight, {x, 1, 0}, 0u});
  }
  Bvh bvh = build_bvh(tris);
  const double bytes = double(bvh.nodes.size() * sizeof(BvhNode) + 100 * sizeof(uint)) / 100.0;
  CHECK(bvh.stats.bytes_per_triangle() == Approx(bytes));
  const std::string tag = bvh.stats.summary();
  CHECK(tag.rfind("[bvh: " + std::to_string(bvh.nodes.size()) + " nodes, ", 0) == 0);
  CHECK(tag.find(" ms, " + std::to_string(int(std::lround(bytes))) + " B/tri]") != std::string::npos);
}
