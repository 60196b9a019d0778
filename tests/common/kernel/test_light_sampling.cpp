// Light sampling (common/kernel/lights.glsl), compiled as the CPU kernels compile it:
// the mean of 1 / pdf over samples reproduces each light's subtended solid angle, and each
// kind of light's weight and pdf are its formula's. (Picking one light of many:
// test_light_pick.cpp.)
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "common/scene/analytic_scenes.h"
#include "common/scene/scene.h"
#include "cpu/kernel_prelude.h"
#include "tests/support/test_render.h"

namespace {  // internal linkage: each test file compiles its own copy of the kernel code
namespace kernel {
#include "tests/support/light_kernel.h"
}  // namespace kernel
}  // namespace

namespace {


// Solid angle of a triangle seen from the origin (Van Oosterom and Strackee 1983).
double triangle_solid_angle(glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
  double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
  double numerator = glm::dot(a, glm::cross(b, c));
  double denominator = la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
  return std::abs(2.0 * std::atan2(numerator, denominator));
}

}  // namespace

TEST_CASE("light sampling: the mean of 1/pdf is the solid angle a triangle or a sphere subtends",
          "[stage4][lights][statistical]") {
  pt::Scene s;
  uint light = s.add_material(pt::make_diffuse(glm::vec3(0.0f), glm::vec3(1.0f)));
  glm::vec3 p0(-0.4f, 1.0f, -0.3f), p1(0.7f, 1.2f, -0.2f), p2(0.1f, 0.9f, 0.8f);
  s.add_triangle(p0, p1, p2, light);  // facing down, towards the origin
  pt::build_light_table(s);
  kernel::bind_scene(s);
  kernel::rng_seed(1u, 2u, pt::test::test_seed(3));
  const int n = 400000;
  double sum = 0.0, sum2 = 0.0;
  int zero = 0;
  for (int i = 0; i < n; i++) {
    kernel::LightSample ls = kernel::sample_light(glm::vec3(0.0f), glm::vec3(0, 1, 0));
    zero += !(ls.pdf > 0.0f);
    double inv = ls.pdf > 0.0f ? 1.0 / double(ls.pdf) : 0.0;
    sum += inv, sum2 += inv * inv;
  }
  double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
  double want = triangle_solid_angle(glm::dvec3(p0), glm::dvec3(p1), glm::dvec3(p2));
  INFO("mean 1/pdf " << mean << " +- " << se << ", solid angle " << want);
  CHECK(zero == 0);
  CHECK(std::abs(mean - want) < 5.0 * se + 1e-6 * want);

  // A sphere: every sample's 1/pdf is the cone's solid angle 2 pi (1 - cos theta_max).
  pt::Scene t;
  uint lamp = t.add_material(pt::make_diffuse(glm::vec3(0.0f), glm::vec3(2.0f)));
  t.add_sphere({0.0f, 3.0f, 1.0f}, 0.5f, lamp);
  pt::build_light_table(t);
  kernel::bind_scene(t);
  double d2 = 10.0, cone = 2.0 * M_PI * (1.0 - std::sqrt(1.0 - 0.25 / d2));
  for (int i = 0; i < 1000; i++) {
    kernel::LightSample ls = kernel::sample_light(glm::vec3(0.0f), glm::vec3(0, 1, 0));
    REQUIRE(1.0 / ls.pdf == Approx(cone).epsilon(1e-3));
    // The sampled direction lies in the cone and meets the sphere at the returned distance.
    glm::vec3 y = ls.dist * ls.wi;
    CHECK(glm::length(y - glm::vec3(0.0f, 3.0f, 1.0f)) == Approx(0.5f).epsilon(1e-3));
  }
}

TEST_CASE("light sampling: the sampled point's pdf equals the pdf its evaluation returns", "[stage4][lights]") {
  pt::Scene s;
  uint a = s.add_material(pt::make_diffuse(glm::vec3(0.0f), glm::vec3(1.0f)));
  uint b = s.add_material(pt::make_diffuse(glm::vec3(0.0f), glm::vec3(0.5f, 2.0f, 1.0f), true));
  s.add_triangle({-1, 2, -1}, {1, 2, -1}, {0, 2.5f, 1}, a);
  s.add_triangle({2, 0, 0}, {2, 1, 0}, {2, 0, 1}, b);
  pt::build_light_table(s);
  kernel::bind_scene(s, glm::vec3(0.2f));  // with a sky, whose share the pick probability leaves out
  kernel::rng_seed(4u, 5u, pt::test::test_seed(6));
  int checked = 0;
  for (int i = 0; i < 2000; i++) {
    glm::vec3 p(0.1f, 0.2f, 0.3f);
    kernel::LightSample ls = kernel::sample_light(p, glm::vec3(0, 1, 0));
    if (!(ls.pdf > 0.0f) || ls.dist == kernel::kInfinity) continue;  // the sky, or a back face
    kernel::Hit hit = kernel::intersect_scene(kernel::Ray(p, ls.wi), kernel::kInfinity);
    REQUIRE(hit.kind == pt::kPrimTriangle);
    CHECK(hit.t == Approx(ls.dist).epsilon(1e-4));
    CHECK(kernel::triangle_light_pdf(hit.prim, ls.wi, hit.t) == Approx(ls.pdf).epsilon(1e-3));
    checked++;
  }
  CHECK(checked > 500);
}

// Held back from the students' copy (tag [held_back], tools/make_lab_handout.py,
// docs/labs/teachers.md): it spells out lab 4's triangle_light_pdf, which the handout asks for.
TEST_CASE("light sampling: triangle_light_pdf is d^2 / (cos_y area) times the pick, 0 for a back face or no light",
          "[stage4][lights][held_back]") {
  pt::Scene s;
  uint one_sided = s.add_material(pt::make_diffuse(glm::vec3(0.0f), glm::vec3(1.0f)));
  uint two_sided = s.add_material(pt::make_diffuse(glm::vec3(0.0f), glm::vec3(2.0f, 1.0f, 3.0f), true));
  uint wall = s.add_material(pt::make_diffuse(glm::vec3(0.5f)));
  s.add_triangle({0, 2, 0}, {2, 2, 0}, {0, 2, 2}, one_sided);     // area 2, front face down (-y)
  s.add_triangle({0, -1, 0}, {3, -1, 0}, {0, -1, 1}, two_sided);  // area 1.5, front face down
  s.add_triangle({5, 0, 0}, {6, 0, 0}, {5, 1, 0}, wall);          // no light
  pt::build_light_table(s);
  kernel::bind_scene(s);
  REQUIRE(s.lights.size() == 2);
  const double area[2] = {2.0, 1.5};
  // From p to points y of each light: d^2 / (|cos_y| area) times the light's pick probability.
  for (glm::vec3 p : {glm::vec3(0.3f, 0.1f, 0.2f), glm::vec3(-1.0f, 0.5f, 2.0f)}) {
    for (int t = 0; t < 2; t++) {
      for (glm::vec2 b : {glm::vec2(0.2f, 0.3f), glm::vec2(0.6f, 0.1f), glm::vec2(0.05f, 0.9f)}) {
        glm::vec3 y = (1.0f - b.x - b.y) * s.triangles[t].p0 + b.x * s.triangles[t].p1 + b.y * s.triangles[t].p2;
        double d = glm::length(glm::dvec3(y - p)), cos_y = std::abs(double(y.y - p.y)) / d;
        double want = d * d / (cos_y * area[t]) * s.lights[s.triangles[t].light].pick;
        INFO("triangle " << t << ", p " << p.x << " " << p.y << " " << p.z << ", y " << y.x << " " << y.y << " " << y.z);
        CHECK(kernel::triangle_light_pdf(uint(t), glm::normalize(y - p), float(d)) == Approx(want).epsilon(1e-4));
      }
    }
  }
  // The one-sided light seen from above (its back), and a triangle that is no light: 0.
  CHECK(kernel::triangle_light_pdf(0u, glm::vec3(0, -1, 0), 1.0f) == 0.0f);
  CHECK(kernel::triangle_light_pdf(2u, glm::vec3(0, 0, -1), 1.0f) == 0.0f);
}

TEST_CASE("light sampling: a spot light's weight is I falloff / d^2, full within the inner cone, none beyond the outer",
          "[stage4][lights][punctual]") {
  pt::Scene s;
  s.add_material(pt::make_diffuse(glm::vec3(0.5f)));
  const float inner = 0.2f, outer = 0.6f, h = 2.0f;
  s.point_lights.push_back(pt::make_spot_light({0.0f, h, 0.0f}, {0.0f, -1.0f, 0.0f}, {5.0f, 4.0f, 3.0f}, inner, outer));
  pt::build_light_table(s);
  kernel::bind_scene(s);
  for (double theta : {0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.59, 0.61, 0.9}) {
    // The floor point seen from the light at angle theta from its axis.
    glm::vec3 p(float(h * std::tan(theta)), 0.0f, 0.0f);
    kernel::LightSample ls = kernel::sample_point_light(0, p, 0.5f);
    double c = std::cos(theta), t = std::clamp((c - std::cos(outer)) / (std::cos(inner) - std::cos(outer)), 0.0, 1.0);
    double d2 = double(h) * h / (c * c);
    INFO("theta " << theta);
    CHECK(ls.weight.x == Approx(5.0 * t * t / (d2 * 0.5)).margin(1e-6));
    CHECK(ls.weight.z == Approx(3.0 * t * t / (d2 * 0.5)).margin(1e-6));
    CHECK(ls.pdf == 0.0f);  // a delta light
    if (t > 0.0) {
      CHECK(ls.dist == Approx(std::sqrt(d2)));
      CHECK(ls.wi.y == Approx(c));
    }
  }
  CHECK(pt::analytic::spot_falloff(inner, outer, 0.4) ==
        Approx(std::pow((std::cos(0.4) - std::cos(outer)) / (std::cos(inner) - std::cos(outer)), 2.0)));
}

TEST_CASE("light sampling: a directional light arrives from -direction, from infinitely far, with weight E / pick",
          "[stage4][lights][punctual]") {
  pt::Scene s;
  s.add_material(pt::make_diffuse(glm::vec3(0.5f)));
  s.point_lights.push_back(pt::make_directional_light({0.6f, -0.8f, 0.0f}, glm::vec3(2.0f)));
  pt::build_light_table(s);
  kernel::bind_scene(s);
  for (glm::vec3 p : {glm::vec3(0.0f), glm::vec3(1e4f, -3.0f, 7.0f)}) {
    kernel::LightSample ls = kernel::sample_point_light(0, p, 0.25f);
    CHECK(ls.wi.x == Approx(-0.6f));
    CHECK(ls.wi.y == Approx(0.8f));
    CHECK(ls.dist == kernel::kInfinity);
    CHECK(ls.weight.y == Approx(8.0f));
    CHECK(ls.pdf == 0.0f);
  }
}

TEST_CASE("light sampling: spot and directional lights are picked by their power", "[stage4][lights][punctual]") {
  pt::Scene s;
  uint m = s.add_material(pt::make_diffuse(glm::vec3(0.5f)));
  s.add_triangle({-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, m);  // bounds: a 2 x 0 x 2 box, radius sqrt(2)
  s.point_lights = {pt::make_point_light({0, 1, 0}, glm::vec3(1.0f)),
                    pt::make_spot_light({0, 2, 0}, {0, -1, 0}, glm::vec3(1.0f), std::acos(0.9f), std::acos(0.7f)),
                    pt::make_directional_light({0, -1, 0}, glm::vec3(1.0f))};
  pt::build_light_table(s);
  REQUIRE(s.lights.size() == 3);
  // Powers: point 4 pi; spot 2 pi (1 - (0.9 + 0.7) / 2) = 0.4 pi; directional pi r^2 = 2 pi.
  CHECK(s.lights[0].pick == Approx(4.0 / 6.4).epsilon(1e-5));
  CHECK(s.lights[1].pick == Approx(0.4 / 6.4).epsilon(1e-5));
  CHECK(s.lights[2].pick == Approx(2.0 / 6.4).epsilon(1e-5));
}

