// Shading normals in rendered images (issue #46; common/kernel/shading_normal.glsl), on the
// backend under test (pt_tests: the CPU, pt_gpu_tests: Vulkan): a white Lambert plane with a
// strong normal map under a uniform sky is the sky at every pixel (no black facets, no
// light leaks: the fold keeps the albedo), a normal-mapped closed furnace is Le / (1 - a),
// smooth vertex normals remove a coarse sphere's facet edges, and a normal map of scale 0
// is the plane without one. Tolerances come from the images' own variance (image_checks.h).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "stage4_direct_indirect/kernels.h"
#include "tests/support/analytic_suite.h"
#include "tests/support/image_checks.h"
#include "tests/support/shading_scenes.h"
#include "tests/support/test_render.h"
#include "tests/support/texture_scenes.h"

using namespace pt;
using namespace pt::test;

namespace {

// The largest difference of horizontally adjacent pixels whose centres both lie within 0.7
// of the sphere's centre (inside the icosahedron's outline, away from its silhouette), in the orthographic
// view of half-extent 1.2 at size x size.
double largest_neighbour_step(const Film& film, int size) {
  double worst = 0.0;
  auto inside = [&](int x, int y) {
    double sx = (2.0 * (x + 0.5) / size - 1.0) * 1.2, sy = (1.0 - 2.0 * (y + 0.5) / size) * 1.2;
    return sx * sx + sy * sy < 0.49;
  };
  for (int y = 0; y < size; y++) {
    for (int x = 0; x + 1 < size; x++) {
      if (!inside(x, y) || !inside(x + 1, y)) continue;
      worst = std::max(worst, std::abs(film.mean(x + 1, y).y - film.mean(x, y).y));
    }
  }
  return worst;
}

// check_scene (every pixel and the image mean) for stages 2, 3 and 5. Stage4 finds direct
// light by light sampling alone, and under a shading normal the folded BSDF times the
// geometric cosine does not vanish at the geometric horizon, where the light's pdf does (the
// sky's cosine-weighted pdf, a neighbouring triangle's solid angle): its samples then have a
// tail of index 2 (docs/shading_normals.md, "What it costs"), unbiased but of unbounded
// variance, which the batches' standard error underestimates (over 20 seeds: means 0.6% low
// at t = 6.8 once, a pixel test failed once). Its image mean is checked with a 1.5% floor.
void check_shaded_scene(const StageKernels& kernels, const Scene& scene, const ExpectedImage& want, RenderSettings s,
                        double relative_floor) {
  if (std::string(kernels.name) != "stage4_direct_indirect") return check_scene(kernels, scene, want, s, relative_floor);
  std::vector<Film> batches = render_batches(kernels, scene, s, 8);
  CHECK(channel_means_ratio(batches, want, 1e-3, std::max(relative_floor, 0.015)) <= 1.0);
}

}  // namespace

TEST_CASE("shading normals: a normal-mapped white plane under a uniform sky is the sky at every pixel, stages 2 to 5",
          "[shading_normals][statistical]") {
  const Scene scene = bumpy_plane(1.0f);
  REQUIRE((scene_feature_mask(scene, glm::vec3(kSky)) & kFeatureShadingNormals) != 0u);
  const ExpectedImage sky(16 * 16, kSky);
  std::uint32_t seed = test_seed(46300);
  for (const StageKernels& kernels : path_tracing_stages()) {
    INFO(kernels.name);
    RenderSettings s = settings(16, 16, 64, seed += 100);
    s.sky = glm::vec3(kSky);
    // Every pixel within its Monte Carlo interval of the sky (so within [0, sky] up to its
    // noise: neither darker facets nor light leaking above it), and the image mean the sky.
    check_shaded_scene(kernels, scene, sky, s, kRounding);
  }
}

TEST_CASE("shading normals: a normal-mapped closed furnace is Le / (1 - albedo), stages 2 to 5",
          "[shading_normals][statistical]") {
  const Scene scene = bumpy_furnace(0.5f, 1.0f);
  const ExpectedImage want(12 * 12, glm::dvec3(2.0));
  std::uint32_t seed = test_seed(46400);
  for (const StageKernels& kernels : path_tracing_stages()) {
    INFO(kernels.name);
    RenderSettings s = settings(12, 12, 32, seed += 100);
    s.roulette = kRouletteThroughput;
    check_shaded_scene(kernels, scene, want, s, 0.0);
  }
}

TEST_CASE("shading normals: smooth vertex normals remove a coarse sphere's facet edges", "[shading_normals][stage4]") {
  const int size = 48;
  RenderSettings s = settings(size, size, 16, test_seed(46500));
  Film flat = render_on_test_backend(stage4::kernels(), coarse_sphere(false), s).film;
  Film smooth = render_on_test_backend(stage4::kernels(), coarse_sphere(true), s).film;
  double flat_step = largest_neighbour_step(flat, size), smooth_step = largest_neighbour_step(smooth, size);
  INFO("largest neighbour step: flat " << flat_step << ", smooth " << smooth_step);
  // An icosahedron's faces meet at 41.8 degrees: under a sun from the viewer a facet edge is
  // a step of about a fifth of the brightest pixel; smooth normals leave the slope alone.
  CHECK(flat_step > 0.1);
  CHECK(smooth_step < 0.5 * flat_step);
}

TEST_CASE("shading normals: a normal map of scale 0 renders the plane without one", "[shading_normals][stage4]") {
  Scene plain = bumpy_plane(0.0f, false, glm::vec3(0.7f));
  Scene mapped = bumpy_plane(0.0f, true, glm::vec3(0.7f));
  for (Scene* scene : {&plain, &mapped}) {
    scene->point_lights.push_back(make_point_light(glm::vec3(0.3f, 1.0f, 1.5f), glm::vec3(2.0f)));
    build_light_table(*scene);
  }
  RenderSettings s = settings(16, 16, 8, test_seed(46600));
  Film a = render_on_test_backend(stage4::kernels(), plain, s).film;
  Film b = render_on_test_backend(stage4::kernels(), mapped, s).film;
  // The same random numbers, the same directions up to the rounding of the frame.
  double worst = 0.0;
  for (int y = 0; y < 16; y++) {
    for (int x = 0; x < 16; x++) {
      glm::dvec3 va = a.mean(x, y), vb = b.mean(x, y);
      worst = std::max(worst, glm::length(va - vb) / std::max(glm::length(va), 1e-3));
    }
  }
  CHECK(worst < 1e-4);
}
