// Collapsing the binary BVH into the CPU's wide tree (wide_bvh.h): the step after the
// article's GPU section, which ends "yet without an acceleration structure". Nodes of 8
// children and leaves of up to 8 triangles laid out as arrays, from the binary tree alone:
// every box is one of its boxes, every triangle lands in exactly one leaf block.
#include "cpu/wide_bvh.h"

#include <algorithm>
#include <stdexcept>

#include "common/scene/bvh.h"

namespace pt {

namespace {

float surface_area(const BvhNode& n) {
  const glm::vec3 d = glm::max(n.hi - n.lo, glm::vec3(0.0f));
  return d.x * d.y + d.y * d.z + d.z * d.x;
}

// The binary nodes that become one wide node's children.
struct Slots {
  uint node[kWideWidth];
  int count = 0;
};

class Collapser {
 public:
  Collapser(const Bvh& bvh, std::span<const Triangle> triangles, unsigned leaf_max, WideBvh& out)
      : bvh_(bvh), triangles_(triangles), leaf_max_(leaf_max), out_(out), count_(bvh.nodes.size(), 0u) {
    // Triangles below each node: children come after their parent, so in reverse order.
    for (std::size_t i = bvh.nodes.size(); i-- > 0;) {
      const BvhNode& n = bvh.nodes[i];
      count_[i] = n.count > 0u ? n.count : count_[n.first_or_left] + count_[n.first_or_left + 1u];
    }
  }

  void build() {
    out_.nodes.reserve(bvh_.nodes.size() / 8u + 1u);
    out_.blocks.reserve(bvh_.nodes.size() / 4u + 1u);
    if (is_leaf(0u)) {  // a root of few triangles: one node with one child, the root's box
      out_.nodes.emplace_back();
      Slots root;
      root.node[0] = 0u, root.count = 1;
      fill_node(0u, root);
      return;
    }
    build_node(0u);
  }

 private:
  bool is_leaf(uint node) const { return bvh_.nodes[node].count > 0u || count_[node] <= leaf_max_; }

  // A wide node for the binary inner node `node`: its children, then the children of the
  // largest inner ones among them, until there are 8.
  std::int32_t build_node(uint node) {
    Slots slots;
    slots.node[0] = bvh_.nodes[node].first_or_left, slots.node[1] = slots.node[0] + 1u, slots.count = 2;
    while (slots.count < kWideWidth) {
      int pick = -1;
      float area = -1.0f;
      for (int i = 0; i < slots.count; i++) {
        if (is_leaf(slots.node[i])) continue;
        const float a = surface_area(bvh_.nodes[slots.node[i]]);
        if (a > area) pick = i, area = a;
      }
      if (pick < 0) break;
      const uint left = bvh_.nodes[slots.node[pick]].first_or_left;
      slots.node[pick] = left;
      slots.node[slots.count++] = left + 1u;
    }
    const std::size_t index = out_.nodes.size();
    out_.nodes.emplace_back();
    fill_node(index, slots);
    return std::int32_t(index);
  }

  void fill_node(std::size_t index, const Slots& slots) {
    WideNode n{};
    for (int i = 0; i < kWideWidth; i++) {
      n.child[i] = kWideEmpty;
      for (int k = 0; k < 3; k++) n.lo[k][i] = 0.0f, n.hi[k][i] = 0.0f;
    }
    for (int i = 0; i < slots.count; i++) {
      const BvhNode& b = bvh_.nodes[slots.node[i]];
      for (int k = 0; k < 3; k++) n.lo[k][i] = b.lo[k], n.hi[k][i] = b.hi[k];
      n.child[i] = is_leaf(slots.node[i]) ? ~build_leaf(slots.node[i]) : build_node(slots.node[i]);
    }
    out_.nodes[index] = n;
  }

  // One block with every triangle below `node`, in the binary tree's leaf order.
  std::int32_t build_leaf(uint node) {
    WideBlock block{};
    for (int i = 0; i < kWideWidth; i++) block.index[i] = -1;
    int lane = 0, top = 0;
    uint todo[2 * kWideWidth];  // a subtree of at most 8 triangles has at most 8 leaves
    todo[top++] = node;
    while (top > 0) {
      const BvhNode& n = bvh_.nodes[todo[--top]];
      if (n.count == 0u) {
        todo[top++] = n.first_or_left + 1u, todo[top++] = n.first_or_left;
        continue;
      }
      for (uint k = 0; k < n.count; k++, lane++) block.index[lane] = std::int32_t(bvh_.indices[n.first_or_left + k]);
    }
    out_.blocks.push_back(block);
    return std::int32_t(out_.blocks.size() - 1);
  }

 public:
  // The blocks' coordinates, once every block knows its triangles. The triangles lie in the
  // scene's order, not the tree's, so nearly every one is a cache miss: fetched a few blocks
  // ahead, the misses overlap (issue 50: the collapse's CPU time on 1.3 M triangles).
  void fill_blocks() {
    constexpr std::size_t ahead = 8;
    HugeVector<WideBlock>& blocks = out_.blocks;
    for (std::size_t b = 0; b < blocks.size(); b++) {
      if (b + ahead < blocks.size()) {
        for (std::int32_t t : blocks[b + ahead].index) {
          if (t >= 0) __builtin_prefetch(&triangles_[std::size_t(t)]), __builtin_prefetch(&triangles_[std::size_t(t)].p2);
        }
      }
      WideBlock& block = blocks[b];
      for (int lane = 0; lane < kWideWidth && block.index[lane] >= 0; lane++) {
        const Triangle& tri = triangles_[std::size_t(block.index[lane])];
        const glm::vec3* p[3] = {&tri.p0, &tri.p1, &tri.p2};
        for (int v = 0; v < 3; v++) {
          for (int a = 0; a < 3; a++) block.v[3 * v + a][lane] = (*p[v])[a];
        }
      }
    }
  }

 private:

  const Bvh& bvh_;
  std::span<const Triangle> triangles_;
  unsigned leaf_max_;
  WideBvh& out_;
  std::vector<uint> count_;
};

}  // namespace

WideBvh build_wide_bvh(const Bvh& bvh, std::span<const Triangle> triangles, unsigned leaf_max) {
  static_assert(kBvhMaxLeaf <= unsigned(kWideWidth), "a binary leaf must fit one block");
  if (leaf_max < 1u || leaf_max > unsigned(kWideWidth)) throw std::invalid_argument("build_wide_bvh: leaf_max");
  WideBvh out;
  if (bvh.nodes.empty()) return out;
  out.source = bvh.nodes.data();
  out.shading = triangles.data();
  for (int k = 0; k < 3; k++) out.root_lo[k] = bvh.nodes[0].lo[k], out.root_hi[k] = bvh.nodes[0].hi[k];
  Collapser collapser(bvh, triangles, leaf_max, out);
  collapser.build();
  collapser.fill_blocks();
  return out;
}

}  // namespace pt
