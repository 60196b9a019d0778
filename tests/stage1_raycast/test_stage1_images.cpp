// stage1_raycast (Eq. 2) against images known in closed form, on the backend under test:
// pt_tests runs these on the CPU, pt_gpu_tests on Vulkan. Each pixel of a stage1 image is
// colour x (fraction of the pixel's jittered samples that hit the shape), a binomial
// count, tested exactly with Šidák-corrected significance over all pixels.
#include <catch2/catch.hpp>

#include <cmath>

#include "common/scene/analytic_scenes.h"
#include "common/scene/scene_loading.h"
#include "stage1_raycast/kernels.h"
#include "tests/support/analytic_images.h"
#include "tests/support/statistics.h"
#include "tests/support/test_render.h"

using namespace pt;
using namespace pt::test;

namespace {

// Checks an image whose pixels are colour x Binomial(spp, coverage) / spp over a black sky.
void check_coverage_image(const Film& film, const std::vector<double>& coverage, glm::vec3 color) {
  const std::uint64_t n = film.spp();
  const double pixels = double(film.width()) * film.height();
  const double alpha_pixel = sidak_alpha(1e-3, pixels);
  double hits_total = 0.0, expected_total = 0.0, variance_total = 0.0;
  int failures = 0;
  for (int y = 0; y < film.height(); y++) {
    for (int x = 0; x < film.width(); x++) {
      glm::dvec3 v = film.mean(x, y);
      double c = coverage[std::size_t(y) * film.width() + x];
      // Every sample is the colour or the sky, so the hit count is a whole number.
      double hits = v.x / color.x * double(n);
      INFO("pixel " << x << "," << y << " value " << v.x << "," << v.y << "," << v.z << " coverage " << c);
      REQUIRE(std::abs(hits - std::round(hits)) < 1e-3);
      REQUIRE(std::abs(v.y / color.y * double(n) - hits) < 1e-3);
      REQUIRE(std::abs(v.z / color.z * double(n) - hits) < 1e-3);
      // Ray generation rounds in float: a pixel just touching an edge may see a stray hit.
      double p = std::clamp(c, 1e-6, 1.0 - 1e-6);
      if (binomial_two_sided_p(std::uint64_t(std::llround(hits)), n, p) < alpha_pixel) {
        failures++;
        UNSCOPED_INFO("pixel " << x << "," << y << ": " << hits << " hits of " << n << ", coverage " << c);
      }
      hits_total += std::round(hits);
      expected_total += c * double(n);
      variance_total += c * (1.0 - c) * double(n);
    }
  }
  CHECK(failures == 0);
  // The whole image: a bias too small for any single pixel still shows in the sum.
  double z = (hits_total - expected_total) / std::sqrt(std::max(variance_total, 1.0));
  INFO("hits " << hits_total << " expected " << expected_total << " z " << z);
  CHECK(std::abs(z) < normal_two_sided_quantile(1e-3));
}

}  // namespace

TEST_CASE("stage1: a sphere before a perspective camera covers each pixel as in closed form",
          "[stage1][statistical][analytic]") {
  const int size = 48;
  Scene scene = make_builtin_scene("sphere");
  RenderResult r = render_on_test_backend(stage1::kernels(), scene, settings(size, size, 256, test_seed(11)));
  check_coverage_image(r.film, sphere_coverage(size, size), analytic::SphereScene().color);
}

TEST_CASE("stage1: a turned square under an orthographic camera covers each pixel as in closed form",
          "[stage1][statistical][analytic]") {
  const int size = 48;
  Scene scene = make_builtin_scene("quad");
  RenderResult r = render_on_test_backend(stage1::kernels(), scene, settings(size, size, 256, test_seed(12)));
  check_coverage_image(r.film, quad_coverage(size, size), analytic::QuadScene().color);
}

TEST_CASE("stage1: inside the furnace box every pixel is the walls' emission", "[stage1][analytic]") {
  Scene scene = make_builtin_scene("furnace");
  RenderResult r = render_on_test_backend(stage1::kernels(), scene, settings(32, 32, 4, test_seed(13)));
  float le = analytic::FurnaceScene().emission;
  for (int y = 0; y < 32; y++) {
    for (int x = 0; x < 32; x++) {
      glm::dvec3 v = r.film.mean(x, y);
      INFO("pixel " << x << "," << y);
      REQUIRE(v.x == Approx(le).epsilon(1e-6));
      REQUIRE(v.y == Approx(le).epsilon(1e-6));
      REQUIRE(v.z == Approx(le).epsilon(1e-6));
    }
  }
}

TEST_CASE("stage1: the same seed gives the same image, another seed another", "[stage1]") {
  Scene scene = make_builtin_scene("cornell");
  RenderResult a = render_on_test_backend(stage1::kernels(), scene, settings(40, 30, 3, 5));
  RenderResult b = render_on_test_backend(stage1::kernels(), scene, settings(40, 30, 3, 5));
  RenderResult c = render_on_test_backend(stage1::kernels(), scene, settings(40, 30, 3, 6));
  CHECK(a.film.mean_rgb() == b.film.mean_rgb());
  CHECK(a.film.mean_rgb() != c.film.mean_rgb());
}

TEST_CASE("stage1: rays that leave the scene see the sky", "[stage1]") {
  Scene scene = make_builtin_scene("sphere");
  RenderSettings s = settings(16, 16, 1, 1);
  s.sky = glm::vec3(0.25f, 0.5f, 2.0f);
  RenderResult r = render_on_test_backend(stage1::kernels(), scene, s);
  glm::dvec3 corner = r.film.mean(0, 0);
  CHECK(corner.x == 0.25);
  CHECK(corner.y == 0.5);
  CHECK(corner.z == 2.0);
}
