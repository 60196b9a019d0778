// The analytic images of stages 2-4 (see analytic_suite.h).
#include "tests/support/analytic_suite.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "common/scene/analytic_scenes.h"
#include "common/kernel/scene_types.h"
#include "tests/support/analytic_images.h"
#include "common/scene/scene_loading.h"
#include "tests/support/statistics.h"
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

void check_one_bounce_furnace(const StageKernels& kernels, std::uint32_t seed) {
  for (float albedo : {0.5f, 0.8f}) {
    analytic::FurnaceScene f;
    f.albedo = albedo;
    RenderSettings s = settings(16, 16, 256, seed);
    s.roulette = kRouletteThroughput;
    s.depth_cap = 1;  // the camera hit and its direct light, nothing after
    INFO("albedo " << albedo);
    check_scene(kernels, analytic::make_furnace(f), ExpectedImage(16 * 16, glm::dvec3(f.emission * (1.0 + albedo))), s);
  }
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

void check_light_turned_away(const StageKernels& kernels, std::uint32_t seed, bool triangle) {
  const int size = 12;
  analytic::FloorLightScene a;
  a.triangle = triangle;
  a.turned_away = true;
  Film film(size, size);
  for (const Film& b : render_batches(kernels, analytic::make_floor_light(a), settings(size, size, 64, seed), 2)) {
    film.merge(b);
  }
  double brightest = 0.0;
  for (int y = 0; y < size; y++) {
    for (int x = 0; x < size; x++) {
      glm::dvec3 m = film.mean(x, y);
      brightest = std::max(brightest, std::max(m.x, std::max(m.y, m.z)));
    }
  }
  INFO((triangle ? "triangle" : "square") << " light facing away from the floor");
  CHECK(brightest == 0.0);
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

void check_point_floor(const StageKernels& kernels, int size, std::uint32_t seed, uint kind) {
  analytic::PointFloorScene a;
  a.kind = kind;
  ExpectedImage expected = expected_image(size, size, [&](double x0, double y0, double x1, double y1) {
    auto radiance = [](double sx, double sy, const void* data) {
      const analytic::PointFloorScene& a = *static_cast<const analytic::PointFloorScene*>(data);
      if (a.kind == kPunctualDirectional) return a.floor.albedo * std::cos(double(a.sun_angle)) / M_PI;
      glm::dvec3 p(sx * a.floor.view_half, 0.0, -sy * a.floor.view_half), light(0.0, a.floor.light_height, 0.0);
      double d2 = glm::dot(light - p, light - p), cos_theta = a.floor.light_height / std::sqrt(d2);
      double falloff = a.kind == kPunctualSpot ? analytic::spot_falloff(a.inner, a.outer, std::acos(cos_theta)) : 1.0;
      return a.floor.albedo * falloff * cos_theta / (M_PI * d2);
    };
    // A spot's falloff has a kink at its inner cone: the rule is applied to 8 x 8 cells of
    // the pixel there, which leaves its error far below the test's standard error.
    return glm::dvec3(a.intensity) * rect_average(x0, y0, x1, y1, radiance, &a, a.kind == kPunctualSpot ? 8 : 1);
  });
  RenderSettings s = settings(size, size, 64, seed);
  s.roulette = kRouletteThroughput;
  check_scene(kernels, analytic::make_point_floor(a), expected, s);
}

void check_point_in_sphere(const StageKernels& kernels, std::uint32_t seed) {
  analytic::PointInSphereScene a;
  double want = a.albedo * a.intensity / (M_PI * a.radius * a.radius) / (1.0 - a.albedo);
  RenderSettings s = settings(12, 12, 256, seed);
  s.roulette = kRouletteThroughput;
  check_scene(kernels, analytic::make_point_in_sphere(a), ExpectedImage(144, glm::dvec3(want)), s);
}

void check_agree_on_cornell(const StageKernels& reference, const StageKernels& test, std::uint32_t seed) {
  Scene scene = make_builtin_scene("cornell");
  RenderSettings s = settings(32, 32, 64, seed);
  s.roulette = kRouletteThroughput;
  const int k = 16;  // batches: stage3 sees the small light by chance, its batch means are skewed
  std::vector<Film> a = render_batches(reference, scene, s, k);
  std::vector<Film> b = render_batches(test, scene, s, k);
  const int regions = 17;  // 4 x 4 regions of 8 x 8 pixels, and the whole image
  const double t_crit = student_two_sided_quantile(sidak_alpha(1e-3, regions * 3.0), 2 * k - 2);
  auto region_mean = [](const Film& f, int r, int c) {
    int x0 = r < 16 ? (r % 4) * 8 : 0, y0 = r < 16 ? (r / 4) * 8 : 0, w = r < 16 ? 8 : f.width();
    double m = 0.0;
    for (int y = y0; y < y0 + w; y++)
      for (int x = x0; x < x0 + w; x++) m += f.mean(x, y)[c];
    return m / (w * w);
  };
  int failures = 0;
  for (int r = 0; r < regions; r++) {
    for (int c = 0; c < 3; c++) {
      double ma = 0, mb = 0, va = 0, vb = 0;
      for (int i = 0; i < k; i++) ma += region_mean(a[i], r, c) / k, mb += region_mean(b[i], r, c) / k;
      for (int i = 0; i < k; i++) {
        va += std::pow(region_mean(a[i], r, c) - ma, 2) / (k - 1);
        vb += std::pow(region_mean(b[i], r, c) - mb, 2) / (k - 1);
      }
      double se = std::sqrt(va / k + vb / k);
      double t = se > 0.0 ? (ma - mb) / se : (ma == mb ? 0.0 : 1e9);
      if (std::abs(t) >= t_crit) {
        failures++;
        UNSCOPED_INFO("region " << r << " channel " << c << ": " << reference.name << " " << ma << ", " << test.name
                                << " " << mb << ", t " << t);
      }
    }
  }
  CHECK(failures == 0);
}

}  // namespace pt::test
