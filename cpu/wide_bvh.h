// The CPU's form of the BVH (the step after the article's GPU section, which ends "yet
// without an acceleration structure"): the binary tree of common/scene/bvh.h collapsed
// into nodes of 8 children whose boxes lie side by side as arrays, so that one ray tests
// all 8 at once on SIMD lanes, and leaves of up to 8 triangles laid out as arrays, tested
// at once by the lanes of triangle_lane_ops.h. Built by the CPU backend's set_scene from the
// binary tree it is handed (wide_bvh.cpp), walked by wide_bvh_walk.cpp; the GPU keeps
// walking the binary tree (common/kernel/bvh.glsl). The same hits as the brute force, bit
// for bit, the lower index on a tie (tests/cpu/test_wide_bvh.cpp).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "common/base/huge_pages.h"
#include "common/kernel/scene_types.h"

namespace pt {

struct Bvh;

constexpr int kWideWidth = 8;  // children per node, triangles per leaf block
// A node's child: >= 0 a node, < 0 the leaf block ~child, kWideEmpty an unused slot.
constexpr std::int32_t kWideEmpty = INT32_MIN;

// 8 children: their boxes (as the binary tree's nodes have them) axis by axis, and refs;
// aligned to cache lines (256 bytes), so that no 32-byte load of the walk straddles two.
struct alignas(64) WideNode {
  float lo[3][kWideWidth];
  float hi[3][kWideWidth];
  std::int32_t child[kWideWidth];
};

// A leaf's triangles as arrays: v[3 p + k][i] is axis k of vertex p of lane i's triangle;
// index[i] its index in the scene's triangles[], -1 for an empty lane (all zeros: its zero
// determinant rejects it, as TriangleSoa's padding). 320 bytes, aligned to cache lines too.
struct alignas(64) WideBlock {
  float v[9][kWideWidth];
  std::int32_t index[kWideWidth];
};

struct WideBvh {
  HugeVector<WideNode> nodes;  // root at 0; empty when there are no triangles (huge pages: huge_pages.h)
  HugeVector<WideBlock> blocks;
  const BvhNode* source = nullptr;  // the binary tree's nodes it was built from
  float root_lo[3] = {}, root_hi[3] = {};  // the root's box: the walk's margin for every box
  // The triangles it was built of: the walk prefetches the best hit's after each leaf, since
  // the kernel reads that triangle next (intersect.glsl's surface_at), a cache miss on a large
  // mesh. Only a hint: a prefetch never faults, even of a pointer gone stale.
  const Triangle* shading = nullptr;
};

// Collapses the binary tree: a subtree of at most leaf_max (1 ... 8) triangles becomes one
// leaf block, and a node takes in the children of its largest (by surface area) inner
// children until it has 8. Every box is a binary node's box, so the walk is conservative
// wherever the binary one is.
WideBvh build_wide_bvh(const Bvh& bvh, std::span<const Triangle> triangles, unsigned leaf_max = 8);

// A ray as the walk takes it: origin and direction, and make_ray_shear()'s result.
struct WideRay {
  float origin[3];
  float dir[3];
  int kx, ky, kz;
  float sx, sy, sz;
};
// A hit: the triangle's index, -1 for none (a bound of t alone, or a sphere's hit).
struct WideHit {
  float t, b1, b2;
  std::int32_t prim;
};

// The nearest hit of `best` and every triangle; a hit at best.t wins when its index is lower
// than best.prim (best.prim -1: only nearer hits count, as hit_triangle()'s t < best.t).
// lanes: 0 the best the CPU has (AVX-512, AVX2, else 4 lanes); 4 or 8 ask for that width
// (the tests run both on any x86-64 CPU with AVX2).
WideHit wide_bvh_nearest(const WideBvh& bvh, const WideRay& ray, WideHit best, int lanes = 0);
// Whether some triangle is hit closer than t_max.
bool wide_bvh_occluded(const WideBvh& bvh, const WideRay& ray, float t_max, int lanes = 0);

}  // namespace pt
