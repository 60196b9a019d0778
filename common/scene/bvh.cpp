// The BVH builder (bvh.h): top-down binned SAH (Wald, "On fast construction of SAH-based
// bounding volume hierarchies", 2007) over the triangles' boxes, 16 bins per axis, O(n log n).
// The acceleration structure the article's GPU section still lacks ("yet without an
// acceleration structure"); the kernels walk it in common/kernel/bvh.glsl.
#include "common/scene/bvh.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

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

class Builder {
 public:
  explicit Builder(std::span<const Triangle> triangles) {
    boxes_.resize(triangles.size());
    centroids_.resize(triangles.size());
    for (std::size_t i = 0; i < triangles.size(); i++) {
      const Triangle& t = triangles[i];
      boxes_[i].extend(t.p0), boxes_[i].extend(t.p1), boxes_[i].extend(t.p2);
      centroids_[i] = 0.5f * boxes_[i].lo + 0.5f * boxes_[i].hi;  // no overflow near FLT_MAX
    }
  }

  Bvh build() {
    Bvh bvh;
    if (boxes_.empty()) return bvh;
    bvh_ = &bvh;
    bvh.indices.resize(boxes_.size());
    for (std::size_t i = 0; i < boxes_.size(); i++) bvh.indices[i] = uint(i);
    bvh.nodes.reserve(2 * boxes_.size());
    bvh.nodes.push_back(BvhNode{});
    split(0, 0, uint(boxes_.size()), 0);
    return bvh;
  }

 private:
  // A node over indices[begin, end): its box, then a leaf or two children.
  void split(uint node, uint begin, uint end, unsigned depth) {
    std::vector<uint>& idx = bvh_->indices;
    Box box, centroids;
    for (uint i = begin; i < end; i++) box.extend(boxes_[idx[i]]), centroids.extend(centroids_[idx[i]]);
    store_box(bvh_->nodes[node], box);
    bvh_->stats.depth = std::max(bvh_->stats.depth, depth);
    const uint n = end - begin;
    uint mid = n <= 1 ? begin : sah_split(begin, end, box, centroids, depth);
    if (mid == begin) {
      if (n <= kBvhMaxLeaf) {  // a leaf: the SAH found no split that pays, or one triangle
        bvh_->nodes[node].first_or_left = begin, bvh_->nodes[node].count = n;
        return;
      }
      mid = median_split(begin, end, centroids);
    }
    if (depth + 1 >= kBvhStackSize) throw std::logic_error("BVH deeper than the traversal's stack");
    const uint left = uint(bvh_->nodes.size());
    bvh_->nodes.push_back(BvhNode{}), bvh_->nodes.push_back(BvhNode{});
    bvh_->nodes[node].first_or_left = left, bvh_->nodes[node].count = 0u;
    split(left, begin, mid, depth + 1);
    split(left + 1, mid, end, depth + 1);
  }

  // The box rounded outward by one float step: a superset of the triangles' exact box.
  static void store_box(BvhNode& node, const Box& box) {
    const float inf = std::numeric_limits<float>::infinity();
    for (int k = 0; k < 3; k++) {
      node.lo[k] = std::nextafter(box.lo[k], -inf);
      node.hi[k] = std::nextafter(box.hi[k], inf);
    }
  }

  // The best binned SAH split of indices[begin, end) into [begin, mid) and [mid, end), or
  // begin when a leaf costs less (cost: 1 per node visited, 1 per triangle tested) or no
  // bin boundary separates the centroids.
  uint sah_split(uint begin, uint end, const Box& box, const Box& centroids, unsigned depth) {
    if (depth >= kSahDepth) return begin;
    const double parent = box.half_area();
    double best_cost = std::numeric_limits<double>::infinity();
    int best_axis = -1, best_bin = 0;
    for (int axis = 0; axis < 3; axis++) {
      const double lo = centroids.lo[axis], extent = double(centroids.hi[axis]) - lo;
      if (!(extent > 0.0) || !std::isfinite(extent)) continue;
      Box bins[kBins];
      uint counts[kBins] = {};
      for (uint i = begin; i < end; i++) {
        uint p = bvh_->indices[i];
        int b = bin_of(centroids_[p][axis], lo, extent);
        bins[b].extend(boxes_[p]), counts[b]++;
      }
      // Sweep from the right, then from the left: the cost of a cut after bin b.
      double right_area[kBins];
      uint right_count[kBins];
      Box acc;
      uint count = 0;
      for (int b = kBins - 1; b > 0; b--) {
        acc.extend(bins[b]), count += counts[b];
        right_area[b] = acc.half_area(), right_count[b] = count;
      }
      acc = Box{}, count = 0;
      for (int b = 0; b < kBins - 1; b++) {
        acc.extend(bins[b]), count += counts[b];
        if (count == 0 || right_count[b + 1] == 0) continue;
        double cost = double(count) * acc.half_area() + double(right_count[b + 1]) * right_area[b + 1];
        if (cost < best_cost) best_cost = cost, best_axis = axis, best_bin = b;
      }
    }
    if (best_axis < 0) return begin;
    const uint n = end - begin;
    const double split_cost = parent > 0.0 ? 1.0 + best_cost / parent : 1.0 + double(n);
    if (n <= kBvhMaxLeaf && split_cost >= double(n)) return begin;
    const double lo = centroids.lo[best_axis], extent = double(centroids.hi[best_axis]) - lo;
    auto in_left = [&](uint p) { return bin_of(centroids_[p][best_axis], lo, extent) <= best_bin; };
    return uint(std::partition(bvh_->indices.begin() + begin, bvh_->indices.begin() + end, in_left) -
                bvh_->indices.begin());
  }

  static int bin_of(float c, double lo, double extent) {
    int b = int((double(c) - lo) / extent * kBins);
    return std::clamp(b, 0, kBins - 1);
  }

  // Halves indices[begin, end) at the median centroid of the widest axis (ties by index).
  uint median_split(uint begin, uint end, const Box& centroids) {
    glm::dvec3 d = glm::dvec3(centroids.hi) - glm::dvec3(centroids.lo);
    int axis = d.x >= d.y && d.x >= d.z ? 0 : d.y >= d.z ? 1 : 2;
    const uint mid = begin + (end - begin) / 2;
    auto before = [&](uint a, uint b) {
      float ca = centroids_[a][axis], cb = centroids_[b][axis];
      return ca < cb || (!(cb < ca) && a < b);
    };
    std::nth_element(bvh_->indices.begin() + begin, bvh_->indices.begin() + mid, bvh_->indices.begin() + end, before);
    return mid;
  }

  std::vector<Box> boxes_;
  std::vector<glm::vec3> centroids_;
  Bvh* bvh_ = nullptr;
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
  const auto start = std::chrono::steady_clock::now();
  Bvh bvh = Builder(triangles).build();
  bvh.stats.nodes = bvh.nodes.size();
  bvh.stats.triangles = triangles.size();
  bvh.stats.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return bvh;
}

}  // namespace pt
