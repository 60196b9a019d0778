// The bounding volume hierarchy over a scene's triangles, built on the host by the binned
// surface area heuristic and handed to the kernels as flat arrays (common/kernel/bvh.glsl
// walks it). Not in the article, whose GPU section ends "yet without an acceleration
// structure": this is the step after it. Spheres stay brute force (scenes have few).
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "common/kernel/scene_types.h"

namespace pt {

// What the summary line says about a BVH (common/app/summary.cpp).
struct BvhStats {
  std::size_t nodes = 0;
  std::size_t triangles = 0;
  unsigned depth = 0;         // levels below the root
  double build_seconds = 0.0;
  double bytes_per_triangle() const;
  std::string summary() const;  // "[bvh: 23 nodes, 0.1 ms, 40 B/tri]"
};

struct Bvh {
  std::vector<BvhNode> nodes;  // root at 0; empty when there are no triangles
  std::vector<uint> indices;   // the leaves' triangles: indices into the scene's triangles[]
  BvhStats stats;
};

// Most triangles in one leaf: a node with more is always split.
constexpr unsigned kBvhMaxLeaf = 4;
static_assert(kBvhMaxLeaf < (1u << kBvhCountBits), "the walk's stack keeps a leaf's count in kBvhCountBits bits");
// Most triangles a BVH takes: its nodes (fewer than twice the triangles) and the leaves'
// first entries then fit the stack's 32 - kBvhCountBits bits (scene_types.h).
constexpr std::size_t kBvhMaxTriangles = std::size_t(1) << (31 - kBvhCountBits);

// Builds the hierarchy in O(n log n): every primitive index lands in exactly one leaf, a
// child's box lies inside its parent's, every triangle inside its leaf's box, and the
// depth stays below kBvhStackSize (scene_types.h). More than kBvhMaxTriangles: pt::Error,
// exit 3.
Bvh build_bvh(std::span<const Triangle> triangles);

}  // namespace pt
