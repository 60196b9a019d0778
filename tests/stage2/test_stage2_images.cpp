// stage2_montecarlo (Eq. 3) against images known in closed form, on the backend under
// test (pt_tests: CPU, pt_gpu_tests: Vulkan). Tolerances come from the variance the film
// estimates: each pixel by a Šidák-corrected z-test, each channel's image mean by a t-test
// over independent batches (tests/support/image_checks.h).
#include <catch2/catch.hpp>

#include <cmath>

#include "common/analytic_scenes.h"
#include "common/scene_loading.h"
#include "stage2_montecarlo/kernels.h"
#include "tests/support/analytic_images.h"
#include "tests/support/image_checks.h"
#include "tests/support/lambert.h"
#include "tests/support/test_render.h"

using namespace pt;
using namespace pt::test;

namespace {

constexpr int kBatches = 8;

// Renders batches, merges them into one film for the per-pixel test, and runs both tests.
void check_scene(const Scene& scene, const ExpectedImage& expected, RenderSettings s) {
  std::vector<Film> batches = render_batches(stage2::kernels(), scene, s, kBatches);
  Film all(s.width, s.height);
  for (const Film& b : batches) all.merge(b);
  CHECK(check_pixels(all, expected).passed());
  CHECK(channel_means_ratio(batches, expected) <= 1.0);
}

glm::dvec3 constant(double v) { return glm::dvec3(v); }

}  // namespace

TEST_CASE("stage2: furnace box, albedo 0.5, emission 1: every pixel is Le / (1 - albedo) = 2",
          "[stage2][statistical][analytic]") {
  analytic::FurnaceScene f;
  Scene scene = analytic::make_furnace(f);
  double want = f.emission / (1.0 - f.albedo);
  check_scene(scene, ExpectedImage(16 * 16, constant(want)), settings(16, 16, 256, test_seed(100)));
}

TEST_CASE("stage2: a diffuse sphere under a uniform sky is albedo x sky, the sky elsewhere",
          "[stage2][statistical][analytic]") {
  const int size = 24;
  Scene scene = analytic::make_sphere({});
  glm::dvec3 sky(0.5, 1.0, 2.0), albedo(analytic::SphereScene().color);
  std::vector<double> c = sphere_coverage(size, size);
  ExpectedImage expected(c.size());
  for (std::size_t i = 0; i < c.size(); i++) expected[i] = c[i] * albedo * sky + (1.0 - c[i]) * sky;
  RenderSettings s = settings(size, size, 256, test_seed(200));
  s.sky = glm::vec3(sky);
  check_scene(scene, expected, s);
}

TEST_CASE("stage2: a diffuse floor under a square light matches Lambert's formula pixel by pixel",
          "[stage2][statistical][analytic]") {
  const int size = 20;
  analytic::FloorLightScene a;
  Scene scene = analytic::make_floor_light(a);
  ExpectedImage expected = expected_image(size, size, [&](double x0, double y0, double x1, double y1) {
    // Screen (sx, sy) sees the floor point (sx * view, 0, -sy * view).
    auto radiance = [](double sx, double sy, const void* data) {
      const analytic::FloorLightScene& a = *static_cast<const analytic::FloorLightScene*>(data);
      double l = a.light_half, h = a.light_height;
      std::vector<glm::dvec3> light = {{-l, h, -l}, {l, h, -l}, {l, h, l}, {-l, h, l}};
      glm::dvec3 p(sx * a.view_half, 0.0, -sy * a.view_half);
      return a.albedo / M_PI * polygon_irradiance(light, p, {0.0, 1.0, 0.0}, 1.0);
    };
    return glm::dvec3(a.emission) * rect_average(x0, y0, x1, y1, radiance, &a);
  });
  check_scene(scene, expected, settings(size, size, 512, test_seed(300)));
}

TEST_CASE("stage2: a mirror reflects an emitter straight back as F0 x Le", "[stage2][statistical][analytic]") {
  analytic::MirrorScene a;
  Scene scene = analytic::make_mirror(a);
  glm::dvec3 want = glm::dvec3(a.f0) * glm::dvec3(a.emission);
  check_scene(scene, ExpectedImage(12 * 12, want), settings(12, 12, 256, test_seed(400)));
}

TEST_CASE("stage2: a glass slab of ior 1 is invisible; of ior 1.5 it transmits (1 - R) / (1 + R)",
          "[stage2][statistical][analytic]") {
  for (float ior : {1.0f, 1.5f}) {
    analytic::GlassSlabScene a;
    a.ior = ior;
    double r = std::pow((ior - 1.0) / (ior + 1.0), 2.0);
    double want = a.emission * (1.0 - r) / (1.0 + r);
    INFO("ior " << ior << ": transmittance " << want);
    check_scene(analytic::make_glass_slab(a), ExpectedImage(12 * 12, constant(want)),
                settings(12, 12, 256, test_seed(500)));
  }
}
