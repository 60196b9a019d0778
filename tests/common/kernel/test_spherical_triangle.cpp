// stage5_mis's light-sampling machinery (issue #18, its list of tests; beyond the article),
// compiled as the CPU kernels compile it (the GPU compiles the same source):
//  - spherical triangles (common/kernel/spherical_triangle.glsl): Van Oosterom and Strackee's
//    solid angle against the angle excess in long double, from tiny triangles to nearly a
//    hemisphere; Arvo's 1995 sampling uniform over 64 sub-triangles (chi-square), its two
//    steps (the sub-triangle's area, the cosine along the arc) within 1e-4 of the exact
//    mapping, and every sample inside the triangle; over random triangles of solid angle
//    kMinSphericalTriangle to kMaxSphericalTriangle, round, skewed and slivers;
//  - the light strategy's pdf (common/kernel/lights.glsl): a sample of
//    sample_light_by(.., kTriangleBySolidAngle) carries the pdf that light_pdf (or
//    sky_light_pdf) gives the surface its direction reaches, for triangles by solid angle
//    and by area (the fallback), spheres from outside and inside, and the sky; and each
//    sampler's pdf integrates to 1 (the mean of 1/pdf is the light's solid angle);
//  - the power heuristic (common/kernel/mis.glsl): the two weights sum to 1, never NaN.
// Tags: [mis] marks the tests of lab 6's functions (docs/labs/lab6.md: power_heuristic, and
// light_pdf through triangle_light_pdf_by_solid_angle), which grade it; [solid_angle] the
// tests of the sampling by solid angle, which call neither.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "common/scene/scene.h"
#include "cpu/kernel_prelude.h"
#include "tests/support/chi2.h"
#include "tests/support/statistics.h"
#include "tests/support/test_render.h"

namespace {  // internal linkage: each test file compiles its own copy of the kernel code
namespace kernel {
#include "cpu/kernel_begin.h"
#include "common/kernel/rng.glsl"
#include "common/kernel/camera.glsl"
#include "common/kernel/intersect.glsl"
#include "common/kernel/sampling.glsl"
#include "common/kernel/bsdf.glsl"
#include "common/kernel/spawn.glsl"
#include "common/kernel/lights.glsl"
#include "cpu/kernel_support.h"  // and through it mis.glsl (kernel_definitions.glsl)
#include "tests/support/kernel_scene_binding.h"
}  // namespace kernel
}  // namespace

using namespace pt::test;

namespace {

// ---------------------------------------------------------------------------------------
// Reference geometry in long double (x86: 64-bit mantissa), independent of the kernel's.

struct L3 {
  long double x, y, z;
};
L3 ld(glm::vec3 v) { return {v.x, v.y, v.z}; }
L3 ld(glm::dvec3 v) { return {v.x, v.y, v.z}; }
L3 operator+(L3 a, L3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
L3 operator-(L3 a, L3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
L3 operator*(long double s, L3 a) { return {s * a.x, s * a.y, s * a.z}; }
long double dot(L3 a, L3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
L3 cross(L3 a, L3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
long double length(L3 a) { return std::sqrt(dot(a, a)); }
L3 normalized(L3 a) { return (1.0L / length(a)) * a; }
long double det(L3 a, L3 b, L3 c) { return dot(a, cross(b, c)); }

// The angle of the spherical triangle at a: between the planes through a, b and a, c.
long double vertex_angle(L3 a, L3 b, L3 c) {
  L3 nb = cross(a, b), nc = cross(a, c);
  return std::atan2(length(cross(nb, nc)), dot(nb, nc));
}

// The solid angle by Girard's theorem: the angle excess A + B + C - pi (directions need not
// be unit: they are normalised here).
long double excess_area(L3 a, L3 b, L3 c) {
  a = normalized(a), b = normalized(b), c = normalized(c);
  return vertex_angle(a, b, c) + vertex_angle(b, c, a) + vertex_angle(c, a, b) - 3.14159265358979323846264L;
}

// The solid angle by Van Oosterom and Strackee in long double, well defined also for a
// degenerate triangle (a sub-triangle of area 0).
long double vos_area(L3 a, L3 b, L3 c) {
  a = normalized(a), b = normalized(b), c = normalized(c);
  return 2.0L * std::atan2(std::abs(det(a, b, c)), 1.0L + dot(a, b) + dot(b, c) + dot(c, a));
}

// How far outside its triangle a sample may lie: 1e-6 rad (16 float ulps of a unit vector),
// plus 1e-4 of the triangle's angular size (the square root of its solid angle): an edge
// moved by that changes the share of the triangle near it by about 1e-4.
long double edge_tolerance(long double area) { return 1e-6L + 1e-4L * std::sqrt(area); }

// A generator of uniform numbers for the tests' own choices (the kernel's samples come from
// its own streams, or from these where a test hands the kernel its u).
struct Rng {
  std::mt19937_64 g;
  explicit Rng(std::uint64_t seed) : g(seed) {}
  double uniform() { return double(g() >> 11) * 0x1.0p-53; }                 // [0, 1)
  float uniform_float() { return float(g() >> 40) * 0x1.0p-24f; }            // [0, 1), exactly
  double between(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  glm::dvec3 unit() {
    double z = 1.0 - 2.0 * uniform(), r = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = 2.0 * M_PI * uniform();
    return {r * std::cos(phi), r * std::sin(phi), z};
  }
};

// A spherical triangle as the kernel gets it: float unit vectors (normalised in float).
struct Tri {
  glm::vec3 a, b, c;
  long double area = 0.0L;  // the exact solid angle of these float vectors
  std::string shape;
};

glm::vec3 to_unit_float(glm::dvec3 v) { return glm::normalize(glm::vec3(v)); }

Tri finish(glm::dvec3 a, glm::dvec3 b, glm::dvec3 c, const char* shape) {
  Tri t{to_unit_float(a), to_unit_float(b), to_unit_float(c), 0.0L, shape};
  t.area = excess_area(ld(t.a), ld(t.b), ld(t.c));
  return t;
}

enum class Shape { kRound, kSkewed, kSliver };

// A random spherical triangle of solid angle `target` (found by bisection):
//  - round: three vertices at one polar angle about a random axis, about 120 degrees apart;
//    near 2 pi they lie close to a great circle (a nearly-hemisphere triangle);
//  - skewed: polar angles in proportion 0.3..1 and azimuth gaps 0.2..pi - 0.2 apart;
//  - sliver: two vertices 0.3..1.5 rad apart and the third just off the arc between them
//    (aspect ratios up to about 1000 at solid angle 1e-3).
// The vertices' order and orientation are shuffled: every vertex may be Arvo's "a".
Tri make_triangle(double target, Shape shape, Rng& r) {
  glm::dvec3 axis = r.unit();
  glm::dvec3 t = glm::normalize(glm::cross(axis, std::abs(axis.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
  glm::dvec3 s = glm::cross(axis, t);
  Tri tri;
  if (shape == Shape::kSliver) {
    double L = r.between(0.3, 1.5), f = r.between(0.3, 0.7);
    glm::dvec3 a = axis, b = std::cos(L) * axis + std::sin(L) * t;
    glm::dvec3 m = std::cos(f * L) * axis + std::sin(f * L) * t;  // on the arc a..b
    double lo = 0.0, hi = 10.0;
    for (int i = 0; i < 200; i++) {
      double h = 0.5 * (lo + hi);
      (finish(a, b, m + h * s, "").area < target ? lo : hi) = h;
    }
    tri = finish(a, b, m + 0.5 * (lo + hi) * s, "sliver");
  } else {
    double phi[3], m[3] = {1.0, 1.0, 1.0};
    double phi0 = r.between(0.0, 2.0 * M_PI);
    for (;;) {
      double g1, g2;
      if (shape == Shape::kRound) g1 = 2.0 * M_PI / 3.0 + r.between(-0.3, 0.3), g2 = 2.0 * M_PI / 3.0 + r.between(-0.3, 0.3);
      else g1 = r.between(0.2, M_PI - 0.2), g2 = r.between(0.2, M_PI - 0.2);
      double g3 = 2.0 * M_PI - g1 - g2;
      if (g3 < 0.2 || g3 > M_PI - 0.2) continue;
      phi[0] = phi0, phi[1] = phi0 + g1, phi[2] = phi0 + g1 + g2;
      break;
    }
    if (shape == Shape::kSkewed && target < 3.0) m[1] = r.between(0.3, 1.0), m[2] = r.between(0.3, 1.0);
    auto at = [&](double theta) {
      glm::dvec3 v[3];
      for (int k = 0; k < 3; k++) {
        double th = theta * m[k];
        v[k] = std::cos(th) * axis + std::sin(th) * (std::cos(phi[k]) * t + std::sin(phi[k]) * s);
      }
      return finish(v[0], v[1], v[2], shape == Shape::kRound ? "round" : "skewed");
    };
    double lo = 0.0, hi = 0.5 * M_PI;
    for (int i = 0; i < 200; i++) {
      double theta = 0.5 * (lo + hi);
      (at(theta).area < target ? lo : hi) = theta;
    }
    tri = at(0.5 * (lo + hi));
  }
  // Shuffle the order (which vertex is Arvo's a) and the orientation.
  int rot = int(r.uniform() * 3.0);
  for (int k = 0; k < rot; k++) std::swap(tri.a, tri.b), std::swap(tri.b, tri.c);
  if (r.uniform() < 0.5) std::swap(tri.b, tri.c);
  return tri;
}

// Solid angles log-spaced over the range that is sampled by solid angle, both ends included.
std::vector<double> sampled_areas(int n) {
  std::vector<double> v;
  double lo = double(kernel::kMinSphericalTriangle) * 1.001, hi = double(kernel::kMaxSphericalTriangle) * 0.999;
  for (int i = 0; i < n; i++) v.push_back(lo * std::pow(hi / lo, double(i) / (n - 1)));
  return v;
}

// The test triangles: every solid angle in every shape (slivers up to 0.3 sr).
std::vector<Tri> test_triangles(Rng& r, int areas) {
  std::vector<Tri> list;
  for (double area : sampled_areas(areas)) {
    list.push_back(make_triangle(area, Shape::kRound, r));
    list.push_back(make_triangle(area, Shape::kSkewed, r));
    if (area <= 0.3) list.push_back(make_triangle(area, Shape::kSliver, r));
  }
  return list;
}

// The kernel's solid angle of t (seen from the origin), and its sample at u for the solid
// angle `area` (the kernel's own, as lights.glsl passes it).
float kernel_area(const Tri& t) { return kernel::spherical_triangle(glm::vec3(0.0f), t.a, t.b, t.c).area; }

glm::vec3 kernel_sample(const Tri& t, float area, float ux, float uy) {
  kernel::SphericalTriangle s = kernel::spherical_triangle(glm::vec3(0.0f), t.a, t.b, t.c);
  s.area = area;
  return kernel::spherical_triangle_sample(s, glm::vec2(ux, uy));
}

std::string describe(const Tri& t) {
  std::ostringstream o;
  o.precision(9);
  o << t.shape << " triangle of solid angle " << double(t.area) << ": a (" << t.a.x << ", " << t.a.y << ", " << t.a.z
    << ") b (" << t.b.x << ", " << t.b.y << ", " << t.b.z << ") c (" << t.c.x << ", " << t.c.y << ", " << t.c.z << ")";
  return o.str();
}

// How far (radians) w lies outside the spherical triangle a, b, c: the largest distance
// beyond one of its edges' great circles (0 or less inside).
long double outside_by(L3 a, L3 b, L3 c, L3 w) {
  a = normalized(a), b = normalized(b), c = normalized(c), w = normalized(w);
  long double s = det(a, b, c) > 0.0L ? 1.0L : -1.0L;
  long double worst = -1.0L;
  const L3 v[3] = {a, b, c};
  for (int k = 0; k < 3; k++) {
    L3 n = cross(v[k], v[(k + 1) % 3]);
    worst = std::max(worst, -s * dot(n, w) / length(n));  // sin of the distance beyond the edge
  }
  return std::asin(std::clamp(worst, -1.0L, 1.0L));
}

}  // namespace

TEST_CASE("spherical triangles: the solid angle matches the angle excess, from tiny triangles to nearly a hemisphere",
          "[stage5][solid_angle]") {
  // spherical_triangle's tan(omega / 2) = |a . (b x c)| / (1 + a.b + b.c + c.a) in
  // float against Girard's A + B + C - pi in long double, on the same float vectors. In
  // float the triple product of nearly parallel unit vectors has an absolute error of up to
  // a few 1e-8 (products of unit components, eps = 6e-8): up to 1e-4 of the solid angle near
  // 1e-3 sr (measured: 2e-5), where the kernel begins to sample by solid angle
  // (kMinSphericalTriangle; by area below). Required: within 1e-4 relative from 1e-3 sr up to
  // nearly 2 pi, and within 2e-7 sr absolute below (where the solid angle only decides which
  // sampler to use).
  Rng r(test_seed(6100));
  double worst_relative = 0.0, worst_absolute_tiny = 0.0;
  int count = 0;
  std::vector<double> targets = {1e-9, 1e-7, 1e-6, 1e-5, 1e-4, 3e-4};
  for (double a : sampled_areas(15)) targets.push_back(a);
  for (double a : {6.22, 6.25, 6.27, 6.28}) targets.push_back(a);  // nearly a hemisphere (2 pi = 6.2832)
  for (double target : targets) {
    for (Shape shape : {Shape::kRound, Shape::kSkewed, Shape::kSliver}) {
      if (shape == Shape::kSliver && target > 0.3) continue;
      for (int rep = 0; rep < 20; rep++) {
        Tri t = make_triangle(target, shape, r);
        double want = double(t.area), got = double(kernel_area(t));
        INFO(describe(t) << "; kernel " << got);
        REQUIRE(std::isfinite(got));
        if (want >= double(kernel::kMinSphericalTriangle)) {
          double rel = std::abs(got - want) / want;
          worst_relative = std::max(worst_relative, rel);
          CHECK(rel <= 1e-4);
        } else {
          double abs_err = std::abs(got - want);
          worst_absolute_tiny = std::max(worst_absolute_tiny, abs_err);
          CHECK(abs_err <= 2e-7);
        }
        count++;
      }
    }
  }
  INFO(count << " triangles: worst relative error from 1e-3 sr " << worst_relative << ", worst absolute below "
             << worst_absolute_tiny);
  CHECK(count > 500);
}

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

TEST_CASE("spherical triangles: Arvo's two steps hold within 1e-4 (the sub-triangle's solid angle, the cosine along its arc)",
          "[stage5][solid_angle]") {
  // Arvo's mapping, exactly: u.x picks the point c' on the arc a..c for which the triangle
  // a, b, c' has u.x times the solid angle (c' = the sample at u.y = 1); u.y places the
  // sample on the arc b..c' with 1 - cos(angle from b) = u.y (1 - cos(b, c')). Both are the
  // sampler's CDFs, checked here in long double to 1e-4 of their range: at the float
  // solid angle the kernel passes (its own error included), for every triangle of the
  // chi-square test's kind, on a 17 x 17 grid of u. The sample must also lie on the arc
  // b..c' (within 1e-4 of the triangle's size) — what makes the two CDFs the whole mapping.
  Rng r(test_seed(6300));
  std::vector<Tri> tris = test_triangles(r, 12);
  double worst_x = 0.0, worst_y = 0.0, worst_arc = 0.0;
  for (const Tri& t : tris) {
    float area = kernel_area(t);
    L3 a = normalized(ld(t.a)), b = normalized(ld(t.b));
    long double size = std::sqrt(t.area);  // the triangle's angular size, roughly
    double tri_x = 0.0, tri_y = 0.0, tri_arc = 0.0;  // this triangle's worst errors, and where
    float at_x = 0.0f, at_y_x = 0.0f, at_y_y = 0.0f;
    for (int i = 0; i <= 16; i++) {
      float ux = float(i) / 16.0f;
      L3 c_sub = normalized(ld(kernel_sample(t, area, ux, 1.0f)));
      double ex = std::abs(double(vos_area(a, b, c_sub) / t.area) - ux);
      if (!(ex <= tri_x)) tri_x = ex, at_x = ux;
      long double range = 0.5L * dot(c_sub - b, c_sub - b);  // 1 - cos(b, c')
      L3 arc_normal = cross(b, c_sub);
      for (int j = 0; j <= 16; j++) {
        float uy = float(j) / 16.0f;
        L3 w = normalized(ld(kernel_sample(t, area, ux, uy)));
        long double one_minus_cos = 0.5L * dot(w - b, w - b);
        double ey = range > 0.0L ? double(std::abs(one_minus_cos - uy * range) / range) : 0.0;
        double arc = length(arc_normal) > 0.0L ? double(std::abs(dot(w, arc_normal)) / length(arc_normal) / size) : 0.0;
        if (!(ey <= tri_y)) tri_y = ey, at_y_x = ux, at_y_y = uy;
        if (!(arc <= tri_arc)) tri_arc = arc;
      }
    }
    INFO(describe(t) << ": the sub-triangle's share is off by " << tri_x << " at u.x " << at_x
                     << "; 1 - cos from b by " << tri_y << " of its range at u (" << at_y_x << ", " << at_y_y
                     << "); off the arc b..c' by " << tri_arc << " of the triangle's size");
    CHECK(tri_x <= 1e-4);
    CHECK(tri_y <= 1e-4);
    CHECK(tri_arc <= 1e-4);
    worst_x = std::max(worst_x, tri_x), worst_y = std::max(worst_y, tri_y), worst_arc = std::max(worst_arc, tri_arc);
  }
  INFO(tris.size() << " triangles: worst CDF errors u.x " << worst_x << ", u.y " << worst_y << ", off the arc " << worst_arc);
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

namespace {

// The light strategy's pdf of a light sample, as light_pdf (or sky_light_pdf) gives it for
// the surface the sample's direction reaches, against the sample's own: within 1e-4
// relative, plus what float rounding does to the distance and the cosine: of the direction
// (a few ulps, 1e-6 rad at most) at grazing incidence (1e-6 / cos_y), and of the points'
// coordinates over a short distance (8 ulps / dist); a pdf by area goes as dist^2 / cos_y,
// three times that. A sample whose ray
// misses its light, or meets it elsewhere, is allowed only within that rounding of the
// light's edge (the triangle's, or the sphere's outline).
struct PdfTally {
  int compared = 0, failed = 0, at_edge = 0;
  int sky = 0, by_solid_angle = 0, tiny_by_area = 0, huge_by_area = 0, sphere_outside = 0, sphere_inside = 0;  // tiny: small or far
  double worst = 0.0;
};

// The angle (radians) by which the direction wi from p lies beyond the nearest edge of any
// light: negative inside a light's outline, positive outside all of them.
double beyond_light_edges(glm::vec3 p, glm::vec3 wi) {
  long double best = 10.0L;
  for (uint i = 0; i < kernel::params.triangle_count; i++) {
    const auto& tri = kernel::triangles[i];
    if (tri.light == pt::kNoLight) continue;
    best = std::min(best, outside_by(ld(tri.p0) - ld(p), ld(tri.p1) - ld(p), ld(tri.p2) - ld(p), ld(wi)));
  }
  for (uint i = 0; i < kernel::params.sphere_count; i++) {
    const auto& s = kernel::spheres[i];
    L3 to_center = ld(s.center) - ld(p);
    long double d = length(to_center);
    if (d <= s.radius) continue;
    L3 w = normalized(ld(wi));
    long double angle = std::atan2(length(cross(w, to_center)), dot(w, to_center));
    best = std::min(best, angle - std::asin((long double)s.radius / d));
  }
  return double(best);
}

void compare_pdf(glm::vec3 p, glm::vec3 n, PdfTally& tally) {
  kernel::LightSample ls = kernel::sample_light_by(p, n, kernel::kTriangleBySolidAngle);
  if (!(ls.pdf > 0.0f)) return;  // a light that faces away
  std::ostringstream where;
  where.precision(9);
  where << "point (" << p.x << ", " << p.y << ", " << p.z << "), direction (" << ls.wi.x << ", " << ls.wi.y << ", "
        << ls.wi.z << "), distance " << ls.dist;
  double want, cos_y = 1.0, rounding = 0.0;
  if (ls.dist == kernel::kInfinity) {
    want = kernel::sky_light_pdf(n, ls.wi);
    tally.sky++;
  } else {
    kernel::Hit hit = kernel::intersect_scene(kernel::Ray(p, ls.wi), kernel::kInfinity);
    if (hit.kind == pt::kPrimTriangle) {
      const auto& tri = kernel::triangles[hit.prim];
      cos_y = std::abs(glm::dot(ls.wi, glm::normalize(glm::cross(tri.p1 - tri.p0, tri.p2 - tri.p0))));
    } else if (hit.kind == pt::kPrimSphere) {
      const auto& s = kernel::spheres[hit.prim];
      cos_y = std::abs(glm::dot(ls.wi, glm::normalize(p + hit.t * ls.wi - s.center)));
    }
    // Float rounding, relative to the distance: of the direction (a few ulps, 1e-6 rad at
    // most) at incidence cos_y, and of the two points' coordinates (8 ulps of the larger).
    glm::vec3 y = p + ls.dist * ls.wi;
    float largest = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z), std::abs(y.x), std::abs(y.y), std::abs(y.z)});
    rounding = 1e-6 / std::max(cos_y, 1e-30) + 8.0 * double(kernel::ulp_above(largest)) / double(ls.dist);
    if (hit.kind == pt::kPrimNone || !(std::abs(hit.t - ls.dist) <= (1e-4 + rounding) * ls.dist)) {
      double beyond = beyond_light_edges(p, ls.wi);
      if (std::abs(beyond) <= 1e-6) {
        tally.at_edge++;
      } else {
        tally.failed++;
        UNSCOPED_INFO(where.str() << ": its ray " << (hit.kind == pt::kPrimNone ? "misses" : "meets another point, at ")
                                  << (hit.kind == pt::kPrimNone ? 0.0 : hit.t) << "; the direction lies " << beyond
                                  << " rad beyond the nearest light edge");
      }
      return;
    }
    want = kernel::light_pdf(p, ls.wi, hit, hit.t);
    if (hit.kind == pt::kPrimTriangle) {
      // Which way the sample was drawn: by solid angle its pdf is the pick over the solid
      // angle, to the bit; else by area (small or distant, or nearly a hemisphere).
      const auto& tri = kernel::triangles[hit.prim];
      kernel::SphericalTriangle seen = kernel::spherical_triangle(p, tri.p0, tri.p1, tri.p2);
      if (ls.pdf == kernel::light_pick_probability(tri.light) / seen.area) tally.by_solid_angle++;
      else if (seen.area <= kernel::kMaxSphericalTriangle) tally.tiny_by_area++;
      else tally.huge_by_area++;
    } else {
      (kernel::inside_sphere_light(kernel::spheres[hit.prim], p) ? tally.sphere_inside : tally.sphere_outside)++;
    }
  }
  double rel = std::abs(want - double(ls.pdf)) / double(ls.pdf);
  tally.compared++;
  tally.worst = std::max(tally.worst, rel);
  if (!(rel <= 1e-4 + 3.0 * rounding)) {
    tally.failed++;
    if (tally.failed <= 5) UNSCOPED_INFO(where.str() << ": sample pdf " << ls.pdf << ", light_pdf " << want << " (cos_y " << cos_y << ")");
  }
}

glm::vec3 random_point(Rng& r, glm::dvec3 lo, glm::dvec3 hi) {
  return glm::vec3(r.between(lo.x, hi.x), r.between(lo.y, hi.y), r.between(lo.z, hi.z));
}

}  // namespace

TEST_CASE("light_pdf: a light sample's pdf is light_pdf's for the surface its direction reaches (triangles by solid angle "
          "and by area, spheres from outside and inside, the sky)",
          "[stage5][mis][lights]") {
  // What stage5_mis's weights rest on: the light strategy's pdf of a direction is the same
  // whether the light sample drew it (ls.pdf) or a BSDF sample found it (light_pdf, from the
  // hit). Within 1e-4 relative, for random shading points and normals.
  Rng r(test_seed(6500));
  SECTION("triangles: by solid angle, and by area (small or far; nearly a hemisphere)") {
    pt::Scene s;
    uint big = s.add_material(pt::make_diffuse(glm::vec3(0.0f), glm::vec3(1.0f)));           // one-sided
    uint medium = s.add_material(pt::make_diffuse(glm::vec3(0.0f), glm::vec3(10.0f), true));  // two-sided
    uint tiny = s.add_material(pt::make_diffuse(glm::vec3(0.0f), glm::vec3(1000.0f), true));
    uint away = s.add_material(pt::make_diffuse(glm::vec3(0.0f), glm::vec3(1.0f)));
    uint floor = s.add_material(pt::make_diffuse(glm::vec3(0.5f)));
    s.add_triangle({-3, 1, -3}, {3, 1, -3}, {0, 1, 3}, big);             // overhead, facing down
    s.add_triangle({-4, 0, -1}, {-4, 0.9f, 0}, {-4, 0, 1}, medium);      // to the side: 0.01..0.1 sr
    s.add_triangle({20, 0.4f, -0.1f}, {20, 0.6f, 0}, {20, 0.4f, 0.1f}, tiny);  // far: 5e-5 sr
    s.add_triangle({-1, 0, 5}, {1, 0, 5}, {0, 0.8f, 5}, away);           // behind, facing away (+z)
    s.add_triangle({-9, -0.5f, -9}, {0, -0.5f, 9}, {9, -0.5f, -9}, floor);
    pt::build_light_table(s);
    REQUIRE(s.lights.size() == 4);
    kernel::bind_scene(s);
    kernel::rng_seed(1u, 2u, test_seed(6510));
    PdfTally tally;
    for (int i = 0; i < 20000; i++) {
      glm::vec3 p = random_point(r, {-1, 0, -1}, {1, 0.9, 1});
      if (i % 4 == 0) p.y = 1.0f - 1e-3f;  // just under the big light: it subtends more than 6.2 sr
      compare_pdf(p, glm::vec3(0, 1, 0), tally);
    }
    INFO(tally.compared << " samples compared (" << tally.by_solid_angle << " by solid angle, " << tally.tiny_by_area
                        << " tiny and " << tally.huge_by_area << " huge by area), worst relative difference "
                        << tally.worst << "; " << tally.at_edge << " on an edge within rounding");
    CHECK(tally.failed == 0);
    CHECK(tally.by_solid_angle > 1000);
    CHECK(tally.tiny_by_area > 1000);
    CHECK(tally.huge_by_area > 1000);
    // A light seen from behind, and a surface that is no light, have no light pdf.
    glm::vec3 p(0.0f, 0.3f, 0.0f);
    for (glm::vec3 target : {glm::vec3(0.0f, 0.3f, 5.0f), glm::vec3(0.0f, -0.5f, 0.3f)}) {
      glm::vec3 wi = glm::normalize(target - p);
      kernel::Hit hit = kernel::intersect_scene(kernel::Ray(p, wi), kernel::kInfinity);
      REQUIRE(hit.kind == pt::kPrimTriangle);
      CHECK(kernel::light_pdf(p, wi, hit, hit.t) == 0.0f);
    }
  }
  SECTION("a two-sided sphere light, from outside (its cone) and from inside (its area)") {
    pt::Scene s;
    uint lamp = s.add_material(pt::make_diffuse(glm::vec3(0.0f), glm::vec3(2.0f), true));
    glm::vec3 center(0.0f, 2.0f, 0.0f);
    const float radius = 0.8f;
    s.add_sphere(center, radius, lamp);
    pt::build_light_table(s);
    kernel::bind_scene(s);
    kernel::rng_seed(3u, 4u, test_seed(6520));
    PdfTally tally;
    for (int i = 0; i < 20000; i++) {
      glm::vec3 p;
      if (i % 2 == 0) {
        do p = random_point(r, {-4, -2, -4}, {4, 6, 4});
        while (glm::length(p - center) < 1.01f * radius);
      } else {
        do p = center + radius * random_point(r, {-1, -1, -1}, {1, 1, 1});
        while (glm::length(p - center) > 0.95f * radius);
      }
      compare_pdf(p, glm::vec3(r.unit()), tally);
    }
    INFO(tally.compared << " samples compared (" << tally.sphere_outside << " from outside, " << tally.sphere_inside
                        << " from inside), worst relative difference " << tally.worst << "; " << tally.at_edge
                        << " on an edge within rounding");
    CHECK(tally.failed == 0);
    CHECK(tally.sphere_outside > 5000);
    CHECK(tally.sphere_inside > 5000);
  }
  SECTION("the sky, beside a triangle light") {
    pt::Scene s;
    uint lamp = s.add_material(pt::make_diffuse(glm::vec3(0.0f), glm::vec3(1.0f), true));
    s.add_triangle({-1, 3, -1}, {1, 3, -1}, {0, 3, 1}, lamp);
    pt::build_light_table(s);
    kernel::bind_scene(s, glm::vec3(0.5f, 1.0f, 2.0f));
    REQUIRE(kernel::params.sky_pick > 0.0f);
    REQUIRE(kernel::params.sky_pick < 1.0f);
    kernel::rng_seed(5u, 6u, test_seed(6530));
    PdfTally tally;
    for (int i = 0; i < 20000; i++) compare_pdf(random_point(r, {-1, 0, -1}, {1, 2, 1}), glm::vec3(r.unit()), tally);
    INFO(tally.compared << " samples compared (" << tally.sky << " of the sky, " << tally.by_solid_angle
                        << " of the triangle), worst relative difference " << tally.worst << "; " << tally.at_edge
                        << " on an edge within rounding");
    CHECK(tally.failed == 0);
    CHECK(tally.sky > 2000);
    CHECK(tally.by_solid_angle > 2000);
    // Below the horizon of the normal the sky is never sampled: its pdf there is 0.
    CHECK(kernel::sky_light_pdf(glm::vec3(0, 1, 0), glm::normalize(glm::vec3(1, -0.1f, 0))) == 0.0f);
  }
}

TEST_CASE("MIS: the power heuristic's two weights sum to 1 and are never NaN, for pdfs from 0 to 3e38",
          "[stage5][mis]") {
  // w(a, b) + w(b, a) = a^2 / (a^2 + b^2) + b^2 / (b^2 + a^2) = 1 whenever either strategy
  // can sample (a or b > 0), within float rounding (a few ulps of 1); both 0 where neither
  // can. Pairs of random pdfs log-uniform over 1e-40 (subnormal) .. 3e38 and the special
  // values 0, the smallest subnormal, 1e-30, 1, 1e30, FLT_MAX and infinity (one side only:
  // infinity against infinity has no ratio).
  Rng r(test_seed(6600));
  std::vector<float> special = {0.0f, std::numeric_limits<float>::denorm_min(), 1e-30f, 1.0f, 1e30f,
                                std::numeric_limits<float>::max(), std::numeric_limits<float>::infinity()};
  auto check_pair = [](float a, float b) {
    float wa = kernel::power_heuristic(a, b), wb = kernel::power_heuristic(b, a);
    INFO("pdfs " << a << " and " << b << ": weights " << wa << " and " << wb);
    bool ok = !std::isnan(wa) && !std::isnan(wb) && wa >= 0.0f && wa <= 1.0f && wb >= 0.0f && wb <= 1.0f;
    if (a > 0.0f || b > 0.0f) ok = ok && std::abs(double(wa) + double(wb) - 1.0) <= 1e-6;
    else ok = ok && wa == 0.0f && wb == 0.0f;
    if (!ok) FAIL_CHECK("weights do not sum as they must");
    return ok;
  };
  int pairs = 0;
  for (float a : special)
    for (float b : special) {
      if (std::isinf(a) && std::isinf(b)) continue;
      check_pair(a, b), pairs++;
    }
  for (int i = 0; i < 200000; i++) {
    float a = float(std::pow(10.0, r.between(-40.0, 38.5))), b = float(std::pow(10.0, r.between(-40.0, 38.5)));
    if (i % 3 == 0) b = a * float(r.between(0.5, 2.0));  // close pdfs, where the weights are near 1/2
    if (i % 7 == 0) b = special[std::size_t(r.uniform() * (special.size() - 1))];  // a finite special value
    check_pair(a, b), pairs++;
  }
  CHECK(kernel::power_heuristic(1.0f, 1.0f) == 0.5f);
  CHECK(kernel::power_heuristic(3.0f, 1.0f) == Approx(0.9).epsilon(1e-6));
  CHECK(pairs > 200000);
}

TEST_CASE("light sampling by solid angle: the mean of 1/pdf is the light's solid angle (each sampler's pdf integrates to 1)",
          "[stage5][solid_angle][statistical]") {
  // E[1/pdf] over a sampler's directions is the measure of the set it samples: the triangle's
  // solid angle (long double, from the float vertices), the sphere's cone 2 pi (1 - cos) from
  // outside, 4 pi from inside. By solid angle, and from outside the sphere, every sample's
  // 1/pdf is that constant, and no sample may be lost (pdf 0). By area (a triangle that
  // lights.glsl leaves to its area: small, distant, or nearly a hemisphere) and from inside
  // the sphere, 1/pdf is random. Each mean must lie within 1e-4 relative (float rounding of
  // the solid angle) plus z standard errors, z at an overall 1e-3 (Šidák over the 32 means
  // at most of this test).
  Rng r(test_seed(6700));
  const double z = normal_two_sided_quantile(sidak_alpha(1e-3, 32.0));
  auto one_light = [](pt::Scene& s) {
    pt::build_light_table(s);
    REQUIRE(s.lights.size() == 1);
    kernel::bind_scene(s);
  };
  auto mean_inverse_pdf = [](glm::vec3 p, int n, int& lost, double& se) {
    double sum = 0.0, sum2 = 0.0;
    lost = 0;
    for (int i = 0; i < n; i++) {
      kernel::LightSample ls = kernel::sample_light_by(p, glm::vec3(0, 1, 0), kernel::kTriangleBySolidAngle);
      double inv = ls.pdf > 0.0f ? 1.0 / double(ls.pdf) : 0.0;
      lost += !(ls.pdf > 0.0f);
      sum += inv, sum2 += inv * inv;
    }
    double mean = sum / n;
    se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
    return mean;
  };
  kernel::rng_seed(7u, 8u, test_seed(6710));
  SECTION("triangles of 1e-3 to 6.2 sr at distances 0.2 to 5: the mean of 1/pdf is the solid angle") {
    int tested = 0, constant = 0;
    for (const Tri& t : test_triangles(r, 8)) {
      // A two-sided planar triangle at random distances along the spherical one's vertices.
      glm::vec3 p(0.3f, -0.2f, 0.1f);
      pt::Scene s;
      uint lamp = s.add_material(pt::make_diffuse(glm::vec3(0.0f), glm::vec3(1.0f), true));
      s.add_triangle(p + float(r.between(0.2, 5.0)) * t.a, p + float(r.between(0.2, 5.0)) * t.b,
                     p + float(r.between(0.2, 5.0)) * t.c, lamp);
      one_light(s);
      const pt::Triangle& tri = s.triangles[0];
      double want = double(excess_area(ld(tri.p0) - ld(p), ld(tri.p1) - ld(p), ld(tri.p2) - ld(p)));
      if (want < double(kernel::kMinSphericalTriangle) || want > double(kernel::kMaxSphericalTriangle)) continue;
      int lost;
      double se, mean = mean_inverse_pdf(p, 4000, lost, se);
      INFO(describe(t) << "; mean 1/pdf " << mean << " +- " << se << ", solid angle " << want);
      CHECK(lost == 0);
      CHECK(std::abs(mean - want) <= z * se + 1e-4 * want);
      tested++;
      constant += se <= 1e-6 * mean;  // every sample drawn by solid angle: one value
    }
    INFO(constant << " of " << tested << " triangles sampled by solid angle");
    CHECK(tested >= 15);
    CHECK(constant >= 5);
  }
  SECTION("a triangle below 1e-3 sr, sampled by its area: E[1/pdf] is its solid angle") {
    glm::vec3 p(0.0f), a(0.05f, 4.0f, -0.04f), b(-0.03f, 4.1f, 0.02f), c(0.04f, 3.9f, 0.05f);
    pt::Scene s;
    uint lamp = s.add_material(pt::make_diffuse(glm::vec3(0.0f), glm::vec3(1.0f), true));
    s.add_triangle(a, b, c, lamp);
    one_light(s);
    double want = double(excess_area(ld(a), ld(b), ld(c)));
    REQUIRE(want < double(kernel::kMinSphericalTriangle));
    int lost;
    double se, mean = mean_inverse_pdf(p, 200000, lost, se);
    INFO("mean 1/pdf " << mean << " +- " << se << ", solid angle " << want);
    CHECK(lost == 0);
    CHECK(std::abs(mean - want) <= z * se + 1e-5 * want);
  }
  SECTION("a sphere from outside (near and 1000 radii away: every 1/pdf is its cone) and from inside (E[1/pdf] = 4 pi)") {
    pt::Scene s;
    uint lamp = s.add_material(pt::make_diffuse(glm::vec3(0.0f), glm::vec3(1.0f), true));
    glm::vec3 center(0.0f, 2.0f, 0.0f);
    const float radius = 0.5f;
    s.add_sphere(center, radius, lamp);
    one_light(s);
    for (double distance : {0.51, 0.6, 1.0, 3.0, 50.0, 500.0}) {
      glm::vec3 p = center - glm::vec3(float(distance), 0.0f, 0.0f);
      double d = double(center.x - p.x);
      double sin2 = double(radius) * radius / (d * d), want = 2.0 * M_PI * sin2 / (1.0 + std::sqrt(1.0 - sin2));
      int lost;
      double se, mean = mean_inverse_pdf(p, 200, lost, se);
      INFO("distance " << distance << ": mean 1/pdf " << mean << ", cone " << want);
      CHECK(lost == 0);
      CHECK(mean == Approx(want).epsilon(1e-4));
    }
    glm::vec3 inside = center + glm::vec3(0.1f, -0.2f, 0.15f);
    int lost;
    double se, mean = mean_inverse_pdf(inside, 200000, lost, se);
    INFO("from inside: mean 1/pdf " << mean << " +- " << se << ", 4 pi " << 4.0 * M_PI);
    CHECK(lost == 0);
    CHECK(std::abs(mean - 4.0 * M_PI) <= z * se + 1e-5 * 4.0 * M_PI);
  }
}
