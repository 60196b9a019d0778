// The spherical triangles of stage5_mis's light-sampling tests (issue #18; beyond the
// article): tests/common/kernel/test_spherical_triangle.cpp,
// test_spherical_triangle_sampling.cpp, test_light_pdf.cpp, test_light_pdf_integral.cpp and
// test_power_heuristic.cpp. Reference geometry in long double, the tests' own random
// numbers, random triangles of a given solid angle (round, skewed, slivers), and the
// kernel's solid angle and sample of one. Include it after the test file's kernel namespace
// (namespace { namespace kernel { ... } }), whose spherical_triangle it calls; everything
// here has internal linkage, like that kernel code.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <glm/glm.hpp>

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
