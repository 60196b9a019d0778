// Where Arvo's 1995 sampling of spherical triangles (common/kernel/spherical_triangle.glsl)
// puts its samples, of stage5_mis's light-sampling machinery (issue #18, its list of tests;
// beyond the article), compiled as the CPU kernels compile it (the GPU compiles the same
// source): uniform over 64 sub-triangles (chi-square), and every sample inside the triangle
// (its ray hits the planar triangle); over random triangles of solid angle
// kMinSphericalTriangle to kMaxSphericalTriangle, round, skewed and slivers
// (tests/support/spherical_triangles.h). The solid angle and the mapping's two steps:
// test_spherical_triangle.cpp. Tags: [solid_angle] the tests of the sampling by solid
// angle, which call none of lab 6's functions.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/scene/scene.h"
#include "cpu/kernel_prelude.h"
#include "tests/support/chi2.h"
#include "tests/support/statistics.h"
#include "tests/support/test_render.h"

namespace {  // internal linkage: each test file compiles its own copy of the kernel code
namespace kernel {
#include "tests/support/light_kernel.h"
}  // namespace kernel
}  // namespace
#include "tests/support/spherical_triangles.h"  // after the kernel: it calls kernel::spherical_triangle

using namespace pt::test;

TEST_CASE("spherical triangles: Arvo's sampling is uniform over 64 sub-triangles (chi-square), from 1e-3 sr to 6.2 sr",
          "[stage5][solid_angle][statistical]") {
  // Each triangle is split 3 times at the midpoints of its edges on the sphere (4^3 = 64
  // sub-triangles); a sub-triangle's expected share of the samples is its solid angle over
  // the whole (long double). Samples are placed by descending the subdivision; one that lies
  // in none of the children at some level (on an edge within rounding) goes to the child it
  // is closest to; sub-triangles expecting fewer than 5 samples are pooled. Šidák over the
  // triangles at an overall 1e-3. And no sample may lie outside the triangle by more than
  // edge_tolerance.
  Rng r(test_seed(6200));
  std::vector<Tri> tris = test_triangles(r, 9);
  const double alpha = sidak_alpha(1e-3, double(tris.size()));
  const int levels = 3, bins = 64, n = 100000;
  int worst_index = 0;
  double worst_p = 1.0;
  for (std::size_t ti = 0; ti < tris.size(); ti++) {
    const Tri& t = tris[ti];
    // The subdivision: triangle i's children are 4i + 1 .. 4i + 4 (a heap), leaves the last 64.
    struct Node {
      L3 a, b, c;
      L3 inward[3];  // unit normals of the edges' great circles, towards the inside
    };
    auto node = [](L3 a, L3 b, L3 c) {
      Node q{a, b, c, {}};
      long double s = det(a, b, c) > 0.0L ? 1.0L : -1.0L;
      const L3 v[3] = {a, b, c};
      for (int k = 0; k < 3; k++) q.inward[k] = s * normalized(cross(v[k], v[(k + 1) % 3]));
      return q;
    };
    // How far w (unit) lies outside q: the largest sine of its distance beyond an edge.
    auto outside = [](const Node& q, L3 w) {
      return std::max({-dot(q.inward[0], w), -dot(q.inward[1], w), -dot(q.inward[2], w)});
    };
    std::vector<Node> nodes = {node(normalized(ld(t.a)), normalized(ld(t.b)), normalized(ld(t.c)))};
    for (std::size_t i = 0; nodes.size() < std::size_t(1 + 4 + 16 + 64); i++) {
      Node p = nodes[i];
      L3 ab = normalized(p.a + p.b), bc = normalized(p.b + p.c), ca = normalized(p.c + p.a);
      nodes.push_back(node(p.a, ab, ca));
      nodes.push_back(node(ab, p.b, bc));
      nodes.push_back(node(ca, bc, p.c));
      nodes.push_back(node(ab, bc, ca));
    }
    const std::size_t first_leaf = 1 + 4 + 16;
    std::vector<double> expected(bins), observed(bins, 0.0);
    long double total = 0.0L;
    for (int k = 0; k < bins; k++) {
      const Node& q = nodes[first_leaf + k];
      long double area = excess_area(q.a, q.b, q.c);
      expected[k] = double(area / t.area) * n;
      total += area;
    }
    INFO(describe(t));
    REQUIRE(double(std::abs(total - t.area) / t.area) < 1e-9);  // the subdivision tiles the triangle
    float area = kernel_area(t);
    int outside_count = 0;
    for (int i = 0; i < n; i++) {
      L3 w = normalized(ld(kernel_sample(t, area, r.uniform_float(), r.uniform_float())));
      if (std::asin(std::min(1.0L, outside(nodes[0], w))) > edge_tolerance(t.area)) outside_count++;
      std::size_t at = 0;
      for (int level = 0; level < levels; level++) {
        std::size_t best = 4 * at + 1;
        long double best_out = 10.0L;
        for (std::size_t child = 4 * at + 1; child <= 4 * at + 4; child++) {
          long double out = outside(nodes[child], w);
          if (out < best_out) best_out = out, best = child;
        }
        at = best;
      }
      std::size_t node_index = at;
      observed[node_index - first_leaf] += 1.0;
    }
    // Sub-triangles expecting fewer than 5 samples (the corners of a nearly-hemisphere
    // triangle) are pooled into one bin.
    double chi2 = 0.0, pooled_observed = 0.0, pooled_expected = 0.0;
    int cells = 0;
    for (int k = 0; k < bins; k++) {
      if (expected[k] < 5.0) {
        pooled_observed += observed[k], pooled_expected += expected[k];
        continue;
      }
      chi2 += (observed[k] - expected[k]) * (observed[k] - expected[k]) / expected[k], cells++;
    }
    if (pooled_expected > 0.0) {
      chi2 += (pooled_observed - pooled_expected) * (pooled_observed - pooled_expected) / pooled_expected, cells++;
    }
    double p = chi2_upper_tail(chi2, cells - 1);
    INFO("chi2 " << chi2 << " (" << cells - 1 << " dof), p " << p << ", level " << alpha << "; samples outside by more than "
                 << double(edge_tolerance(t.area)) << " rad: " << outside_count);
    CHECK(outside_count == 0);
    CHECK(p > alpha);
    if (p < worst_p) worst_p = p, worst_index = int(ti);
  }
  INFO(tris.size() << " triangles; smallest p " << worst_p << ": " << describe(tris[std::size_t(worst_index)]));
  CHECK(tris.size() >= 20);
}

TEST_CASE("spherical triangles: every sample's ray hits the planar triangle", "[stage5][solid_angle][statistical]") {
  // The triangle as a light: vertices at random distances 0.2..5 along the unit vectors
  // from the shading point, the planar triangle they span. Every sample's ray from the point
  // must hit it (Möller-Trumbore in long double: barycentric coordinates in [0, 1] at a
  // positive distance), or miss it by no more than an angle of 1e-6 rad (16 float ulps of a
  // unit vector) plus 1e-4 of the triangle's angular size (edge_tolerance).
  Rng r(test_seed(6400));
  std::vector<Tri> tris = test_triangles(r, 12);
  const int n = 20000;
  long double worst = -1.0L;
  for (const Tri& t : tris) {
    INFO(describe(t));
    L3 p0 = r.between(0.2, 5.0) * ld(t.a), p1 = r.between(0.2, 5.0) * ld(t.b), p2 = r.between(0.2, 5.0) * ld(t.c);
    float area = kernel_area(t);
    int missed = 0;
    long double worst_here = -1.0L;
    for (int i = 0; i < n; i++) {
      L3 w = normalized(ld(kernel_sample(t, area, r.uniform_float(), r.uniform_float())));
      // Möller-Trumbore from the origin: w = p0 + b1 (p1 - p0) + b2 (p2 - p0) at distance d.
      L3 e1 = p1 - p0, e2 = p2 - p0, q = cross(w, e2);
      long double den = dot(e1, q);
      L3 s = (-1.0L) * p0;
      long double b1 = dot(s, q) / den;
      L3 qq = cross(s, e1);
      long double b2 = dot(w, qq) / den, d = dot(e2, qq) / den;
      bool hits = d > 0.0L && b1 >= 0.0L && b2 >= 0.0L && b1 + b2 <= 1.0L;
      // A miss is allowed within rounding of the edge: the angle beyond the triangle p0, p1, p2
      // seen from the origin.
      long double out = hits ? 0.0L : outside_by(p0, p1, p2, w);
      worst_here = std::max(worst_here, out);
      if (!hits && !(out <= edge_tolerance(t.area))) missed++;
    }
    worst = std::max(worst, worst_here);
    INFO(missed << " of " << n << " samples missed; furthest outside " << double(worst_here) << " rad");
    CHECK(missed == 0);
  }
  INFO(tris.size() << " triangles; furthest any sample lay outside: " << double(worst) << " rad");
  CHECK(tris.size() >= 20);
}
