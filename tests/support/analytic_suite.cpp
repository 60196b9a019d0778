// The analytic images of stages 2-4 (see analytic_suite.h).
#include "tests/support/analytic_suite.h"

#include <catch2/catch.hpp>

#include <cmath>

#include "common/scene/analytic_scenes.h"
#include "common/kernel/scene_types.h"
#include "tests/support/analytic_images.h"
#include "tests/support/lambert.h"
#include "tests/support/test_render.h"

namespace pt::test {

void check_scene(const StageKernels& kernels, const Scene& scene, const ExpectedImage& expected, RenderSettings s,
                 double relative_floor) {
  std::vector<Film> batches = render_batches(kernels, scene, s, 8);
  Film all(s.width, s.height);
  for (const Film& b : batches) all.merge(b);
  CHECK(check_pixels(all, expected).passed());
  CHECK(channel_means_ratio(batches, expected, 1e-3, relative_floor) <= 1.0);
}

void check_furnace(const StageKernels& kernels, float albedo, std::uint32_t roulette, std::uint32_t seed) {
  analytic::FurnaceScene f;
  f.albedo = albedo;
  RenderSettings s = settings(16, 16, 256, seed);
  s.roulette = roulette;
  double want = f.emission / (1.0 - f.albedo);
  check_scene(kernels, analytic::make_furnace(f), ExpectedImage(16 * 16, glm::dvec3(want)), s);
}

void check_furnace_sphere(const StageKernels& kernels, float albedo, std::uint32_t seed) {
  analytic::FurnaceSphereScene f;
  f.albedo = albedo;
  RenderSettings s = settings(16, 16, 256, seed);
  s.roulette = kRouletteThroughput;
  double want = f.emission / (1.0 - f.albedo);
  check_scene(kernels, analytic::make_furnace_sphere(f), ExpectedImage(16 * 16, glm::dvec3(want)), s);
}

void check_sky_sphere(const StageKernels& kernels, std::uint32_t seed) {
  const int size = 24;
  glm::dvec3 sky(0.5, 1.0, 2.0), albedo(analytic::SphereScene().color);
  std::vector<double> c = sphere_coverage(size, size);
  ExpectedImage expected(c.size());
  for (std::size_t i = 0; i < c.size(); i++) expected[i] = c[i] * albedo * sky + (1.0 - c[i]) * sky;
  RenderSettings s = settings(size, size, 256, seed);
  s.sky = glm::vec3(sky);
  check_scene(kernels, analytic::make_sphere({}), expected, s);
}

ExpectedImage floor_light_image(const analytic::FloorLightScene& a, int size) {
  return expected_image(size, size, [&](double x0, double y0, double x1, double y1) {
    // Screen (sx, sy) sees the floor point (sx * view, 0, -sy * view).
    auto radiance = [](double sx, double sy, const void* data) {
      const analytic::FloorLightScene& a = *static_cast<const analytic::FloorLightScene*>(data);
      double l = a.light_half, h = a.light_height;
      std::vector<glm::dvec3> light = {{-l, h, -l}, {l, h, -l}, {l, h, l}};
      if (!a.triangle) light.push_back({-l, h, l});
      glm::dvec3 p(sx * a.view_half, 0.0, -sy * a.view_half);
      return a.albedo / M_PI * polygon_irradiance(light, p, {0.0, 1.0, 0.0}, 1.0);
    };
    return glm::dvec3(a.emission) * rect_average(x0, y0, x1, y1, radiance, &a);
  });
}

void check_floor_light(const StageKernels& kernels, std::uint32_t seed, bool triangle) {
  const int size = 20;
  analytic::FloorLightScene a;
  a.triangle = triangle;
  check_scene(kernels, analytic::make_floor_light(a), floor_light_image(a, size), settings(size, size, 1024, seed));
}

void check_mirror(const StageKernels& kernels, std::uint32_t seed) {
  analytic::MirrorScene a;
  glm::dvec3 want = glm::dvec3(a.f0) * glm::dvec3(a.emission);
  check_scene(kernels, analytic::make_mirror(a), ExpectedImage(12 * 12, want), settings(12, 12, 256, seed));
}

void check_glass_slab(const StageKernels& kernels, float ior, std::uint32_t seed) {
  analytic::GlassSlabScene a;
  a.ior = ior;
  double r = std::pow((ior - 1.0) / (ior + 1.0), 2.0);
  double want = a.emission * (1.0 - r) / (1.0 + r);
  INFO("ior " << ior << ": transmittance " << want);
  check_scene(kernels, analytic::make_glass_slab(a), ExpectedImage(12 * 12, glm::dvec3(want)),
              settings(12, 12, 256, seed));
}

}  // namespace pt::test
