// Numerical stability of surfaces at their extremes, as images on the backend under test
// (pt_tests: CPU, pt_gpu_tests: Vulkan): glass of ior 1, 1.0001 and 3, and a glass sphere
// inside a white furnace; camera rays at 89.99 degrees to a plane; GGX roughness down to 0.
// Light transport at its extremes: test_extremes_images.cpp.
#include <catch2/catch.hpp>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "common/scene/analytic_scenes.h"
#include "common/kernel/scene_types.h"
#include "stage3_importance/kernels.h"
#include "stage4_direct_indirect/kernels.h"
#include "tests/support/analytic_suite.h"
#include "tests/support/test_render.h"

using namespace pt;
using namespace pt::test;

namespace {

// An orthographic camera at `eye` looking along the unit `dir`, half-extents xmag, ymag.
CameraDesc orthographic_camera(glm::vec3 eye, glm::vec3 dir, glm::vec3 up, float xmag, float ymag) {
  CameraDesc cam;
  cam.kind = kCameraOrthographic;
  cam.to_world = glm::inverse(glm::lookAt(eye, eye + dir, up));
  cam.xmag = xmag, cam.ymag = ymag;
  return cam;
}

}  // namespace

TEST_CASE("stability: glass of ior 1 is invisible, of ior 1.0001 and 3 transmits (1 - R) / (1 + R)",
          "[stage3][stage4][stability][statistical][analytic]") {
  for (const StageKernels& kernels : {stage3::kernels(), stage4::kernels()}) {
    for (float ior : {1.0f, 1.0001f, 3.0f}) {
      INFO(kernels.name);
      check_glass_slab(kernels, ior, test_seed(7300));
    }
  }
}

TEST_CASE("stability: a closed glass sphere inside a white furnace neither creates nor loses energy",
          "[stage3][stage4][stability][statistical][analytic]") {
  // The furnace's radiance is the same in every direction, so a lossless refracting sphere
  // (radiance scaled by eta^2 entering and 1 / eta^2 leaving, total internal reflection
  // inside) leaves every pixel at Le / (1 - albedo) = 2.
  for (float ior : {1.5f, 3.0f}) {
    for (const StageKernels& kernels : {stage3::kernels(), stage4::kernels()}) {
      Scene scene = analytic::make_furnace({});
      scene.add_sphere(glm::vec3(0.1f, -0.05f, -0.45f), 0.4f, scene.add_material(make_glass(glm::vec3(1.0f), ior)));
      build_light_table(scene);
      RenderSettings s = settings(12, 12, 128, test_seed(7400));
      s.roulette = kRouletteThroughput;
      INFO(kernels.name << ", ior " << ior);
      check_scene(kernels, scene, ExpectedImage(12 * 12, glm::dvec3(2.0)), s);
    }
  }
}

TEST_CASE("stability: camera rays at 89.99 degrees to a diffuse plane under a uniform sky see albedo x sky",
          "[stage3][stage4][stability][statistical][analytic]") {
  // The rays meet the plane 0.01 degrees above it, 4 to 16 units away: a spawned ray that
  // hit the plane again (acne) would darken the pixel.
  const float albedo = 0.5f, sky = 1.0f;
  const float elevation = glm::radians(0.01f);
  Scene scene;
  const float h = 1000.0f;
  add_quad(scene, {-h, 0, h}, {h, 0, h}, {h, 0, -h}, {-h, 0, -h}, scene.add_material(make_diffuse(glm::vec3(albedo))));
  glm::vec3 dir(0.0f, -std::sin(elevation), -std::cos(elevation));
  scene.camera = orthographic_camera(-10.0f * dir, dir, glm::vec3(0, 1, 0), 1.0f, 1e-3f);
  build_light_table(scene);
  RenderSettings s = settings(8, 8, 64, test_seed(7500));
  s.sky = glm::vec3(sky);
  s.roulette = kRouletteThroughput;
  check_scene(stage3::kernels(), scene, ExpectedImage(8 * 8, glm::dvec3(albedo * sky)), s);
  // stage4 finds the sky by light sampling, cosine-weighted: every sample is albedo x sky
  // exactly (f cos / pdf = albedo), unless its shadow ray hit the plane it left (acne).
  RenderResult r = render_on_test_backend(stage4::kernels(), scene, s);
  for (int y = 0; y < 8; y++)
    for (int x = 0; x < 8; x++) {
      INFO("stage4, pixel " << x << "," << y);
      CHECK(r.film.mean(x, y).y == Approx(albedo * sky).epsilon(1e-5));
    }
}

namespace {

// The directional albedo at normal incidence of a white (F = 1) GGX conductor with
// height-correlated Smith masking: at wo = n the visible normals are GGX's own (tan^2
// theta_h = alpha^2 u / (1 - u) for uniform u), and each weighs G2 / G1 = 1 / (1 +
// Lambda(wi)) with wi at 2 theta_h, if above the surface. Midpoint rule in u.
double ggx_albedo_at_normal(double alpha) {
  const int n = 200000;
  double sum = 0.0;
  for (int i = 0; i < n; i++) {
    double u = (i + 0.5) / n;
    double theta_h = std::atan(alpha * std::sqrt(u / (1.0 - u)));
    double theta_i = 2.0 * theta_h;
    if (theta_i >= M_PI / 2.0) continue;
    double t = std::tan(theta_i);
    sum += 1.0 / (1.0 + 0.5 * (std::sqrt(1.0 + alpha * alpha * t * t) - 1.0));
  }
  return sum / n;
}

}  // namespace

TEST_CASE("stability: GGX roughness from 0 to 1: finite images of the closed-form albedo, continuous where "
          "it becomes a perfect mirror", "[stage3][stability][statistical][analytic]") {
  // A white GGX conductor (F0 = 1) seen from straight above under a uniform sky of 1 shows
  // its directional albedo: 1 for a mirror, less as alpha grows (single scattering loses
  // what the microfacets shadow). Below kGgxMirrorAlpha the conductor is a perfect mirror;
  // just above it the GGX image must already be 1 to within 1e-4: no jump at the switch.
  // With throughput roulette a sample is 1 (the path survives with p = G2 / G1) or 0.
  for (float alpha : {0.0f, 0.5f * kGgxMirrorAlpha, 2.0f * kGgxMirrorAlpha, 1e-6f, 1e-4f, 1e-3f, 0.05f, 0.5f, 1.0f}) {
    Scene scene;
    Material metal = make_metal(glm::vec3(1.0f), 0.5f);
    metal.kind = kMaterialConductor;
    metal.alpha = alpha;
    uint m = scene.add_material(metal);
    add_quad(scene, {-100, 0, 100}, {100, 0, 100}, {100, 0, -100}, {-100, 0, -100}, m);
    scene.camera = orthographic_camera(glm::vec3(0, 1, 0), glm::vec3(0, -1, 0), glm::vec3(0, 0, -1), 1.0f, 1.0f);
    build_light_table(scene);
    RenderSettings s = settings(4, 4, 256, test_seed(7600));
    s.sky = glm::vec3(1.0f);
    s.roulette = kRouletteThroughput;
    RenderResult r = render_on_test_backend(stage3::kernels(), scene, s);
    double mean = r.film.mean_luminance();
    double want = alpha < kGgxMirrorAlpha ? 1.0 : ggx_albedo_at_normal(alpha);
    double n = 4.0 * 4.0 * 256.0;
    double tolerance = 5.0 * std::sqrt(want * (1.0 - want) / n) + 1e-4;  // Bernoulli samples
    INFO("alpha " << alpha << ": image mean " << mean << ", closed form " << want << " +- " << tolerance);
    CHECK(r.counters.non_finite == 0);
    CHECK(std::abs(mean - want) <= tolerance);
  }
}
