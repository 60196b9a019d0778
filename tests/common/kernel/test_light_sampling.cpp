// Light sampling (common/kernel/lights.glsl), compiled as the CPU kernels compile it:
// the mean of 1 / pdf over samples reproduces each light's subtended solid angle, and the
// pick probabilities follow the lights' power.
#include <catch2/catch.hpp>

#include <cmath>

#include "common/scene/scene.h"
#include "cpu/kernel_prelude.h"
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
#include "cpu/kernel_support.h"
#include "tests/support/kernel_scene_binding.h"
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

TEST_CASE("light sampling: lights are picked in proportion to their power", "[stage4][lights]") {
  pt::Scene s;
  uint dim = s.add_material(pt::make_diffuse(glm::vec3(0.0f), glm::vec3(1.0f)));
  uint bright = s.add_material(pt::make_diffuse(glm::vec3(0.0f), glm::vec3(3.0f), true));
  s.add_triangle({0, 1, 0}, {1, 1, 0}, {0, 1, 1}, dim);     // area 0.5, one side
  s.add_triangle({0, 2, 0}, {2, 2, 0}, {0, 2, 1}, bright);  // area 1, both sides, 3x brighter
  s.point_lights.push_back(pt::PointLight{glm::vec3(0, 3, 0), 0.0f, glm::vec3(1, 1, 1), 0.0f});
  pt::build_light_table(s);
  REQUIRE(s.lights.size() == 3);
  // Powers: pi 0.5 1, pi 1 2 3, 4 pi 1 -> 0.5 : 6 : 4.
  CHECK(s.lights[0].pick == Approx(0.5 / 10.5).epsilon(1e-5));
  CHECK(s.lights[1].pick == Approx(6.0 / 10.5).epsilon(1e-5));
  CHECK(s.lights[2].pick == Approx(4.0 / 10.5).epsilon(1e-5));
  CHECK(s.lights[2].cumulative == 1.0f);
  CHECK(s.triangles[0].light == 0u);
  kernel::bind_scene(s);
  CHECK(kernel::pick_light(0.0f) == 0u);
  CHECK(kernel::pick_light(0.05f) == 1u);
  CHECK(kernel::pick_light(0.99f) == 2u);
}
