// The environment map in rendered images, every stage, on the backend under test (issue #49;
// beyond the article, whose sky is one colour): a constant map is --sky, a bright patch lights
// a floor as a directional light of its irradiance, a mirror sphere shows a patch where
// reflection and --env-rotate put it, the general kernel agrees. Tolerances from the variance.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "common/scene/analytic_scenes.h"
#include "stage1_raycast/kernels.h"
#include "tests/support/analytic_images.h"
#include "tests/support/analytic_suite.h"
#include "tests/support/environment_scenes.h"
#include "tests/support/image_checks.h"
#include "tests/support/statistics.h"
#include "tests/support/test_render.h"
#include "tests/support/texture_scenes.h"

using namespace pt;
using namespace pt::test;

namespace {

const glm::vec3 kMapRadiance(0.5f, 1.0f, 2.0f);  // the constant map's (and --sky's) radiance
const float kFloorAlbedo = 0.5f;

// The patch of the floor tests: 2 x 2 texels of a 32 x 16 map, columns 20-21 and rows 3-4,
// centred on theta = 45 degrees from +Y, phi = 56.25 degrees from +X towards +Z; the
// bilinear lookup spreads it half a texel further (theta 28 to 62 degrees: all above the
// floor's horizon). About 0.11 sr: a cosine-sampled ray finds it with probability 2.4%.
const Patch kFloorPatch{32, 16, 20, 3, 2, 2, glm::vec3(40.0f, 20.0f, 10.0f)};

// The patch of the mirror tests: 2 x 2 texels of a 48 x 24 map, columns 35-36 and rows 7-8,
// centred on u = 0.75, v = 1/3: +Z raised 30 degrees towards +Y.
const Patch kMirrorPatch{48, 24, 35, 7, 2, 2, glm::vec3(4.0f, 2.0f, 1.0f)};
const glm::dvec3 kMirrorPatchDirection(0.0, 0.5, std::sqrt(0.75));

}  // namespace

TEST_CASE("environment: stage1 shows a constant map as --sky: the background is L, the sphere its colour",
          "[environment][stage1]") {
  const int size = 16;
  Scene scene = analytic::make_sphere({});
  RenderSettings s = settings(size, size, 4, test_seed(49100));
  s.sky = kMapRadiance;
  std::unique_ptr<Backend> backend = make_backend(backend_under_test, stage1::kernels());
  Film sky = render(*backend, scene, s).film;
  s.sky = glm::vec3(0.0f);
  scene.environment = constant_environment(kMapRadiance);
  Film map = render(*backend, scene, s).film;
  const std::vector<double> coverage = sphere_coverage(size, size);
  const glm::dvec3 colour(analytic::SphereScene().color), L(kMapRadiance);
  for (int y = 0; y < size; y++) {
    for (int x = 0; x < size; x++) {
      double c = coverage[std::size_t(y) * size + x];
      if (c != 0.0 && c != 1.0) continue;
      glm::dvec3 want = c == 0.0 ? L : colour, got = map.mean(x, y);
      INFO("pixel " << x << "," << y << ": " << got.x << "," << got.y << "," << got.z);
      for (int i = 0; i < 3; i++) CHECK(got[i] == Approx(want[i]).epsilon(1e-6));
    }
  }
  // The same random numbers: the same image as --sky up to the bilinear blend's rounding.
  CHECK(largest_relative_difference(map, sky) < 1e-6);
}

TEST_CASE("environment: under a constant map a diffuse sphere is albedo x L and the background L, stages 2 to 5",
          "[environment][stage2][stage3][stage4][stage5][statistical]") {
  const int size = 16;
  Scene scene = analytic::make_sphere({});
  scene.environment = constant_environment(kMapRadiance, 37.0f);
  const glm::dvec3 L(kMapRadiance), albedo(analytic::SphereScene().color);
  const std::vector<double> c = sphere_coverage(size, size);
  ExpectedImage want(c.size());
  for (std::size_t i = 0; i < c.size(); i++) want[i] = c[i] * albedo * L + (1.0 - c[i]) * L;
  std::uint32_t seed = test_seed(49200);
  for (const StageKernels& kernels : path_tracing_stages()) {
    INFO(kernels.name);
    RenderSettings s = settings(size, size, 64, seed += 100);
    s.roulette = kRouletteThroughput;
    check_scene(kernels, scene, want, s);
    if (std::string(kernels.name) == "stage2_montecarlo" || std::string(kernels.name) == "stage3_importance") {
      // Stages 2 and 3 draw the same paths under a map as under --sky: the same image.
      std::unique_ptr<Backend> backend = make_backend(backend_under_test, kernels);
      s.spp = 8;
      Film map = render(*backend, scene, s).film;
      s.sky = kMapRadiance;
      CHECK(largest_relative_difference(map, render(*backend, analytic::make_sphere({}), s).film) < 1e-5);
    }
  }
}

TEST_CASE("environment: under a constant map a diffuse floor is albedo x L at every pixel, stages 2 to 5",
          "[environment][stage2][stage3][stage4][stage5][statistical]") {
  const int size = 12;
  Scene scene = environment_floor(kFloorAlbedo);
  scene.environment = constant_environment(kMapRadiance);
  const ExpectedImage want(size * size, double(kFloorAlbedo) * glm::dvec3(kMapRadiance));
  std::uint32_t seed = test_seed(49300);
  for (const StageKernels& kernels : path_tracing_stages()) {
    INFO(kernels.name);
    RenderSettings s = settings(size, size, 32, seed += 100);
    // Stage3 samples the floor's one bounce by its cosine: every sample is albedo x L up to
    // rounding, so its image mean is compared with that rounding allowed.
    check_scene(kernels, scene, want, s, kRounding);
  }
}

TEST_CASE("environment: a small bright patch lights a diffuse floor as a directional light of its irradiance: "
          "albedo E / pi, and with that light beside it twice that, stages 4 and 5",
          "[environment][stage4][stage5][statistical]") {
  const int size = 12;
  Scene scene = environment_floor(kFloorAlbedo);
  // Turned by 37 degrees: E is the same, and a sample drawn where the map is turned wrong
  // would miss the patch.
  const float degrees = 37.0f;
  scene.environment = patch_environment(kFloorPatch, degrees);
  // E computed exactly from the map's texels (floor_irradiance): for each channel, the
  // integral of the bilinear lookup x cos over the hemisphere.
  const glm::dvec3 E = floor_irradiance(*scene.environment);
  // The integration itself: a constant map of radiance L gives a floor pi L.
  REQUIRE(floor_irradiance(*constant_environment(kMapRadiance)).z == Approx(M_PI * kMapRadiance.z).epsilon(1e-9));
  const glm::dvec3 want_value = double(kFloorAlbedo) * E / M_PI;
  const ExpectedImage want(size * size, want_value);
  // The directional light from the patch's centre (theta 45 degrees, turned as the map) whose
  // irradiance on the floor is the same E: E_perpendicular = E / cos(theta).
  const double theta = M_PI / 4.0, phi = 2.0 * M_PI * (21.0 / 32.0 - 0.5), r = degrees * M_PI / 180.0;
  const glm::dvec3 m(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
  const glm::dvec3 towards(std::cos(r) * m.x - std::sin(r) * m.z, m.y, std::sin(r) * m.x + std::cos(r) * m.z);
  // With both, the sky is picked by its power against the sun's (sky_pick_probability).
  Scene both = environment_floor(kFloorAlbedo);
  both.point_lights.push_back(make_directional_light(-glm::vec3(towards), glm::vec3(E / std::cos(theta))));
  build_light_table(both);
  both.environment = scene.environment;
  const ExpectedImage twice(size * size, 2.0 * want_value);
  INFO("E = " << E.x << "," << E.y << "," << E.z << ": every pixel " << want_value.x);
  std::uint32_t seed = test_seed(49400);
  for (const StageKernels& kernels : {stage4::kernels(), stage5::kernels()}) {
    INFO(kernels.name);
    RenderSettings s = settings(size, size, 32, seed += 100);
    s.roulette = kRouletteThroughput;
    check_scene(kernels, scene, want, s);
    // The sun alone gives albedo E / pi too: the tests of stage4 and stage5 prove that
    // closed form (check_point_floor); with the patch beside it the floor is twice as bright.
    check_scene(kernels, both, twice, s);
  }
}

// Stage3 sees the patch only where a cosine-sampled ray happens to hit it (2.4% of them):
// unbiased, with a much wider variance than stages 4 and 5, which sample the map. Measured at
// 16 x 16, 8 x 64 spp (CPU, 20 seeds): the RMS per-pixel error against the closed form is
// 32% for stage3, 1.7% for stage4 and 1.9% for stage5: stage3 needs 280 to 350 times the
// samples for the same error.
TEST_CASE("environment: stage3 finds a small bright patch by BSDF sampling alone: unbiased, at its own, wider "
          "variance",
          "[environment][stage3][stage4][stage5][statistical]") {
  const int size = 16;
  Scene scene = environment_floor(kFloorAlbedo);
  scene.environment = patch_environment(kFloorPatch);
  const glm::dvec3 want_value = double(kFloorAlbedo) * floor_irradiance(*scene.environment) / M_PI;
  const ExpectedImage want(size * size, want_value);
  std::uint32_t seed = test_seed(49500);
  RenderSettings s = settings(size, size, 64, seed);
  s.roulette = kRouletteThroughput;
  std::vector<Film> stage3_batches = render_batches(stage3::kernels(), scene, s, 8);
  // The image mean only: a pixel's 512 samples hold about 12 hits of the patch, too few to
  // estimate its variance (over 20 seeds, 13 runs had more pixels outside their 99% interval
  // than check_pixels allows: pixels whose few hits fell short, with a variance to match).
  CHECK(channel_means_ratio(stage3_batches, want) <= 1.0);
  const double stage3_error = measured_relative_error(merged(stage3_batches), want_value);
  for (const StageKernels& kernels : {stage4::kernels(), stage5::kernels()}) {
    const double error = measured_relative_error(merged(render_batches(kernels, scene, s, 8)), want_value);
    INFO("at " << 8 * s.spp << " spp: stage3's per-pixel error " << stage3_error << ", " << kernels.name << "'s "
               << error);
    // At equal samples stage3's error is many times the light-sampling stages'.
    CHECK(stage3_error > 5.0 * error);
  }
}


namespace {

// The mirror sphere under kMirrorPatch turned by `degrees`, rendered by `kernels` (the
// mirror's F = 1 and the roulette by throughput: every path goes on, each sample is the map
// at a reflected direction): the patch where reflection and the turn put it, nowhere else.
void check_mirror_patch(const StageKernels& kernels, float degrees, std::uint64_t spp, std::uint32_t seed) {
  const int size = 33;
  Scene scene = mirror_sphere();
  scene.environment = patch_environment(kMirrorPatch, degrees);
  // Where the patch is seen: its direction in the map's frame turned back into the world's,
  // map_to_world(m) = (c x - s z, y, s x + c z) (R = 90: +Z up 30 degrees becomes -X up 30).
  const double r = degrees * M_PI / 180.0, c = std::cos(r), sn = std::sin(r);
  const glm::dvec3 m = kMirrorPatchDirection, world(c * m.x - sn * m.z, m.y, sn * m.x + c * m.z);
  const glm::dvec2 p = mirror_sphere_point(world);
  const int px = int(std::floor((p.x + 1.0) / 2.0 * size)), py = int(std::floor((1.0 - p.y) / 2.0 * size));
  INFO(kernels.name << ", env-rotate " << degrees << ": the patch's direction " << world.x << "," << world.y << ","
                    << world.z << " is seen at pixel " << px << "," << py);
  RenderSettings s = settings(size, size, spp, seed);
  s.roulette = kRouletteThroughput;
  Film all = render_on_test_backend(kernels, scene, s).film;
  // The brightest pixel is the predicted one or its neighbour (the patch is 2 texels wide,
  // about 3 pixels in the image) ...
  int bx = 0, by = 0;
  for (int y = 0; y < size; y++)
    for (int x = 0; x < size; x++)
      if (luminance(all.mean(x, y)) > luminance(all.mean(bx, by))) bx = x, by = y;
  INFO("the brightest pixel is " << bx << "," << by);
  CHECK(std::abs(bx - px) <= 1);
  CHECK(std::abs(by - py) <= 1);
  // ... and every pixel is the reference lookup at its reflected directions: black wherever
  // the patch is not reflected, the patch's radiance where it is.
  check_mirror_image(all, *scene.environment, luminance(glm::dvec3(kMirrorPatch.radiance)));
}

}  // namespace

TEST_CASE("environment: a mirror sphere shows a patch where the mirror-reflection law puts it, and --env-rotate 90 "
          "moves it as the rotation formula says",
          "[environment][stage3]") {
  check_mirror_patch(stage3::kernels(), 0.0f, 512, test_seed(49600));
  check_mirror_patch(stage3::kernels(), 90.0f, 512, test_seed(49700));
}

TEST_CASE("environment: a mirror sphere shows a turned patch where reflection puts it in stages 2, 4 and 5 too "
          "(the map seen after a delta bounce)",
          "[environment][stage2][stage4][stage5][statistical]") {
  std::uint32_t seed = test_seed(49800);
  for (const StageKernels& kernels : {stage2::kernels(), stage4::kernels(), stage5::kernels()}) {
    check_mirror_patch(kernels, 90.0f, 256, seed += 100);
  }
}

namespace {

// The scenes of the general kernel's test: a map's lookup (background, mirror), its sampling
// (a diffuse floor in stages 4 and 5), its turn, and a uniform sky without a map.
struct FeatureCase {
  const char* name;
  Scene scene;
  glm::vec3 sky;
};
std::vector<FeatureCase> feature_cases() {
  std::vector<FeatureCase> cases;
  cases.push_back({"floor, patch", environment_floor(kFloorAlbedo), glm::vec3(0.0f)});
  cases.back().scene.environment = patch_environment(kFloorPatch);
  cases.push_back({"mirror sphere, patch turned 90 degrees", mirror_sphere(), glm::vec3(0.0f)});
  cases.back().scene.environment = patch_environment(kMirrorPatch, 90.0f);
  // Without a map the general kernel has the map's code but env_width 0: the uniform sky.
  cases.push_back({"sphere, --sky, no map", analytic::make_sphere({}), kMapRadiance});
  return cases;
}

// Each case with the kernel specialised to its features and with the general one, on one
// backend (the GPU compiles each pipeline once): bit for bit on the CPU, as
// test_specialised.cpp, a few ulps on Vulkan, whose driver may fuse a*b+c in one and not
// the other.
void check_general_kernel(const StageKernels& kernels) {
  std::unique_ptr<Backend> backend = make_backend(backend_under_test, kernels);
  for (const FeatureCase& c : feature_cases()) {
    REQUIRE(((scene_feature_mask(c.scene, c.sky) & kFeatureEnvironment) != 0u) == bool(c.scene.environment));
    RenderSettings s = settings(16, 16, 4, 7);
    s.sky = c.sky;
    s.roulette = kRouletteThroughput;
    std::vector<float> specialised = render(*backend, c.scene, s).film.mean_rgb();
    s.all_features = true;
    std::vector<float> general = render(*backend, c.scene, s).film.mean_rgb();
    INFO(kernels.name << ", " << c.name << " [" << scene_features(c.scene, c.sky) << "]");
    CHECK(max_ulps(specialised, general) <= (backend_under_test == "cpu" ? 0u : 4u));
  }
}

}  // namespace

TEST_CASE("environment: the general kernel renders the same images as the specialised ones, with a map and "
          "without, stage1",
          "[environment][stage1][features]") {
  check_general_kernel(stage1::kernels());
}

// On the CPU every stage; the check build's CPU copy decides each gate at the scene's mask
// at run time, as a specialised GPU kernel does (PT_CPU_RUNTIME_FEATURES,
// cpu/kernel_bindings.h). On the GPU each case is a compile of its own per stage (lavapipe:
// 2-8 s each, stage5's general kernel 18 s; issue #51): stage4, which reads the map in
// both its lookup and its light samples, checks there that the host passes the mask and the
// driver's specialised compile draws the general kernel's image (as test_specialised.cpp).
TEST_CASE("environment: the general kernel renders the same images as the specialised ones, with a map and "
          "without, stages 2 to 5",
          "[environment][stage2][stage3][stage4][stage5][features]") {
  std::vector<StageKernels> stages = {stage4::kernels()};
  if (backend_under_test == "cpu") stages = {stage2::kernels(), stage3::kernels(), stage4::kernels(), stage5::kernels()};
  for (const StageKernels& kernels : stages) check_general_kernel(kernels);
}
