// The BVH builder (bvh.h): top-down binned SAH (Wald, "On fast construction of SAH-based
// bounding volume hierarchies", 2007) over the triangles' boxes, 16 bins per axis, O(n log n),
// the large subtrees on threads of their own.
// The acceleration structure the article's GPU section still lacks ("yet without an
// acceleration structure"); the kernels walk it in common/kernel/bvh.glsl.
#include "common/scene/bvh.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <future>
#include <limits>
#include <stdexcept>
#include <string>

#include "common/base/error.h"

namespace pt {

namespace {

constexpr int kBins = 16;
// Below this depth a node is split where the SAH says; deeper, at the median of its
// centroids, which halves it: the depth stays under kSahDepth + log2(n) < kBvhStackSize.
constexpr unsigned kSahDepth = 30;

struct Box {
  glm::vec3 lo{std::numeric_limits<float>::infinity()};
  glm::vec3 hi{-std::numeric_limits<float>::infinity()};
  void extend(glm::vec3 p) { lo = glm::min(lo, p), hi = glm::max(hi, p); }
  void extend(const Box& b) { lo = glm::min(lo, b.lo), hi = glm::max(hi, b.hi); }
  // Half the surface area, in double: coordinates up to 1e6 and more stay finite.
  double half_area() const {
    if (lo.x > hi.x) return 0.0;
    glm::dvec3 d = glm::dvec3(hi) - glm::dvec3(lo);
    return d.x * d.y + d.y * d.z + d.z * d.x;
  }
};

// A root at least this large builds its two children's subtrees at once: the larger one on
// a thread of its own, into an array of its own that is then appended. The layout depends
// on the size alone, so the tree is the same whatever the number of cores.
constexpr uint kParallelSize = 1u << 16;

class Builder {
 public:
  explicit Builder(std::span<const Triangle> triangles) : refs_(triangles.size()) {
    for (std::size_t i = 0; i < triangles.size(); i++) {
      const Triangle& t = triangles[i];
      refs_[i].box.extend(t.p0), refs_[i].box.extend(t.p1), refs_[i].box.extend(t.p2);
      refs_[i].centroid = 0.5f * refs_[i].box.lo + 0.5f * refs_[i].box.hi;  // no overflow near FLT_MAX
      refs_[i].index = uint(i);
    }
  }

  Bvh build() {
    Bvh bvh;
    if (refs_.empty()) return bvh;
    Subtree tree = subtree(0, uint(refs_.size()), 0);
    bvh.nodes = std::move(tree.nodes);
    bvh.stats.depth = tree.depth;
    bvh.indices.resize(refs_.size());
    for (std::size_t i = 0; i < refs_.size(); i++) bvh.indices[i] = refs_[i].index;
    return bvh;
  }

 private:
  // The nodes of one subtree, its root at 0 and its children's indices its own.
  struct Subtree {
    std::vector<BvhNode> nodes;
    unsigned depth = 0;  // the deepest leaf's depth in the whole tree
  };

  Subtree subtree(uint begin, uint end, unsigned depth) {
    Subtree t;
    t.nodes.reserve(2 * std::size_t(end - begin));
    t.nodes.push_back(BvhNode{});
    split(t, 0, begin, end, depth);
    return t;
  }

  // A node over refs[begin, end): its box, then a leaf or two children.
  void split(Subtree& t, uint node, uint begin, uint end, unsigned depth) {
    Box box, centroids;
    for (uint i = begin; i < end; i++) box.extend(refs_[i].box), centroids.extend(refs_[i].centroid);
    store_box(t.nodes[node], box);
    t.depth = std::max(t.depth, depth);
    const uint n = end - begin;
    uint mid = n <= 1 ? begin : sah_split(begin, end, box, centroids, depth);
    if (mid == begin) {
      if (n <= kBvhMaxLeaf) {  // a leaf: the SAH found no split that pays, or one triangle
        t.nodes[node].first_or_left = begin, t.nodes[node].count = n;
        return;
      }
      mid = median_split(begin, end, centroids);
    }
    if (depth + 1 >= kBvhStackSize) throw std::logic_error("BVH deeper than the traversal's stack");
    const uint left = uint(t.nodes.size());
    t.nodes.push_back(BvhNode{}), t.nodes.push_back(BvhNode{});
    t.nodes[node].first_or_left = left, t.nodes[node].count = 0u;
    if (depth > 0 || n < kParallelSize) {
      split(t, left, begin, mid, depth + 1);
      split(t, left + 1, mid, end, depth + 1);
      return;
    }
    // The two halves of refs[] are disjoint, so the subtrees can be built at once.
    const bool left_larger = mid - begin >= end - mid;
    std::future<Subtree> larger = std::async(std::launch::async, [&] {
      return left_larger ? subtree(begin, mid, depth + 1) : subtree(mid, end, depth + 1);
    });
    if (left_larger) {
      split(t, left + 1, mid, end, depth + 1);
    } else {
      split(t, left, begin, mid, depth + 1);
    }
    append(t, left_larger ? left : left + 1, larger.get());  // get() rethrows the thread's exception
  }

  // Puts a subtree's root in slot `slot` of t and its other nodes after t's, renumbered.
  static void append(Subtree& t, uint slot, const Subtree& sub) {
    const uint offset = uint(t.nodes.size()) - 1u;  // sub's node i >= 1 lands at offset + i
    auto moved = [&](BvhNode n) {
      if (n.count == 0u) n.first_or_left += offset;  // an inner node's children
      return n;
    };
    t.nodes[slot] = moved(sub.nodes[0]);
    for (std::size_t i = 1; i < sub.nodes.size(); i++) t.nodes.push_back(moved(sub.nodes[i]));
    t.depth = std::max(t.depth, sub.depth);
  }

  // The box rounded outward by one float step: a superset of the triangles' exact box.
  static void store_box(BvhNode& node, const Box& box) {
    const float inf = std::numeric_limits<float>::infinity();
    for (int k = 0; k < 3; k++) {
      node.lo[k] = std::nextafter(box.lo[k], -inf);
      node.hi[k] = std::nextafter(box.hi[k], inf);
    }
  }

  // Where the centroids of a node fall into bins along each axis: bin b of axis a holds
  // the centroids c with int((c - lo[a]) * scale[a]) == b (clamped to the bins).
  struct Binning {
    glm::vec3 lo{0.0f}, scale{0.0f};
    bool used[3] = {false, false, false};  // the axis has an extent to cut
    int bin(float c, int axis) const { return std::clamp(int((c - lo[axis]) * scale[axis]), 0, kBins - 1); }
  };

  // The best binned SAH split of refs[begin, end) into [begin, mid) and [mid, end), or
  // begin when a leaf costs less (cost: 1 per node visited, 1 per triangle tested) or no
  // bin boundary separates the centroids. One pass bins the centroids on all three axes.
  uint sah_split(uint begin, uint end, const Box& box, const Box& centroids, unsigned depth) {
    if (depth >= kSahDepth) return begin;
    Binning binning;
    bool any = false;
    for (int axis = 0; axis < 3; axis++) {
      const float extent = centroids.hi[axis] - centroids.lo[axis];
      binning.used[axis] = extent > 0.0f && std::isfinite(extent) && std::isfinite(float(kBins) / extent);
      binning.lo[axis] = centroids.lo[axis];
      binning.scale[axis] = binning.used[axis] ? float(kBins) / extent : 0.0f;
      any = any || binning.used[axis];
    }
    if (!any) return begin;
    Box bins[3][kBins];
    uint counts[3][kBins] = {};
    for (uint i = begin; i < end; i++) {
      const Ref& r = refs_[i];
      for (int axis = 0; axis < 3; axis++) {
        if (!binning.used[axis]) continue;
        const int b = binning.bin(r.centroid[axis], axis);
        bins[axis][b].extend(r.box), counts[axis][b]++;
      }
    }
    const double parent = box.half_area();
    double best_cost = std::numeric_limits<double>::infinity();
    int best_axis = -1, best_bin = 0;
    for (int axis = 0; axis < 3; axis++) {
      if (!binning.used[axis]) continue;
      // Sweep from the right, then from the left: the cost of a cut after bin b.
      double right_area[kBins];
      uint right_count[kBins];
      Box acc;
      uint count = 0;
      double area = 0.0;  // an empty bin changes nothing: small nodes leave most bins empty
      for (int b = kBins - 1; b > 0; b--) {
        if (counts[axis][b]) acc.extend(bins[axis][b]), count += counts[axis][b], area = acc.half_area();
        right_area[b] = area, right_count[b] = count;
      }
      acc = Box{}, count = 0;
      for (int b = 0; b < kBins - 1; b++) {
        if (!counts[axis][b]) continue;  // the same cut as after the bin before
        acc.extend(bins[axis][b]), count += counts[axis][b];
        if (right_count[b + 1] == 0) break;
        double cost = double(count) * acc.half_area() + double(right_count[b + 1]) * right_area[b + 1];
        if (cost < best_cost) best_cost = cost, best_axis = axis, best_bin = b;
      }
    }
    if (best_axis < 0) return begin;
    const uint n = end - begin;
    const double split_cost = parent > 0.0 ? 1.0 + best_cost / parent : 1.0 + double(n);
    if (n <= kBvhMaxLeaf && split_cost >= double(n)) return begin;
    auto in_left = [&](const Ref& r) { return binning.bin(r.centroid[best_axis], best_axis) <= best_bin; };
    return uint(std::partition(refs_.begin() + begin, refs_.begin() + end, in_left) - refs_.begin());
  }

  // Halves refs[begin, end) at the median centroid of the widest axis (ties by index).
  uint median_split(uint begin, uint end, const Box& centroids) {
    glm::dvec3 d = glm::dvec3(centroids.hi) - glm::dvec3(centroids.lo);
    int axis = d.x >= d.y && d.x >= d.z ? 0 : d.y >= d.z ? 1 : 2;
    const uint mid = begin + (end - begin) / 2;
    auto before = [&](const Ref& a, const Ref& b) {
      float ca = a.centroid[axis], cb = b.centroid[axis];
      return ca < cb || (!(cb < ca) && a.index < b.index);
    };
    std::nth_element(refs_.begin() + begin, refs_.begin() + mid, refs_.begin() + end, before);
    return mid;
  }

  // A triangle as the build sees it, kept in the order of the leaves to come: each pass
  // over a node reads its range of refs_ from start to end (no gather through indices).
  struct Ref {
    Box box;
    glm::vec3 centroid;
    uint index;  // into the scene's triangles
  };
  std::vector<Ref> refs_;
};

}  // namespace

double BvhStats::bytes_per_triangle() const {
  if (triangles == 0) return 0.0;
  return double(nodes * sizeof(BvhNode) + triangles * sizeof(uint)) / double(triangles);
}

std::string BvhStats::summary() const {
  char text[128];
  const double ms = build_seconds * 1e3;
  std::snprintf(text, sizeof text, ms < 10.0 ? "[bvh: %zu nodes, %.2f ms, %.0f B/tri]" : "[bvh: %zu nodes, %.0f ms, %.0f B/tri]",
                nodes, ms, bytes_per_triangle());
  return text;
}

Bvh build_bvh(std::span<const Triangle> triangles) {
  if (triangles.size() > kBvhMaxTriangles) {
    throw Error(kExitBadScene, "the scene has " + std::to_string(triangles.size()) + " triangles and the BVH takes at most " +
                                   std::to_string(kBvhMaxTriangles) + "; use a coarser mesh");
  }
  const auto start = std::chrono::steady_clock::now();
  Bvh bvh = Builder(triangles).build();
  bvh.stats.nodes = bvh.nodes.size();
  bvh.stats.triangles = triangles.size();
  bvh.stats.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return bvh;
}

}  // namespace pt
