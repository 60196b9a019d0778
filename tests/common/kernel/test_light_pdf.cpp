// The light strategy's pdf (common/kernel/lights.glsl), of stage5_mis's light-sampling
// machinery (issue #18, its list of tests; beyond the article), compiled as the CPU kernels
// compile it (the GPU compiles the same source): a sample of
// sample_light_by(.., kTriangleBySolidAngle) carries the pdf that light_pdf (or
// sky_light_pdf) gives the surface its direction reaches, for triangles by solid angle and
// by area (the fallback), spheres from outside and inside, and the sky. Each sampler's pdf
// integrating to 1: test_light_pdf_integral.cpp. Tags: [mis] marks the tests of lab 6's
// functions (docs/labs/lab6.md: light_pdf through triangle_light_pdf_by_solid_angle), which
// grade it.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/scene/scene.h"
#include "cpu/kernel_prelude.h"
#include "tests/support/test_render.h"

namespace {  // internal linkage: each test file compiles its own copy of the kernel code
namespace kernel {
#include "tests/support/light_kernel.h"
}  // namespace kernel
}  // namespace
#include "tests/support/spherical_triangles.h"  // after the kernel: it calls kernel::spherical_triangle

using namespace pt::test;

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
