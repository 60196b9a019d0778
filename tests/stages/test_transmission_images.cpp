// KHR_materials_transmission between 0 and 1 in rendered images (issue #46; docs/gltf_material.md,
// "Partial transmission"), on the backend under test (pt_tests: the CPU, pt_gpu_tests: Vulkan),
// read from a glTF file: a plane of transmission T under a uniform sky, black below it, seen in
// perspective, shows the sky times the mixture's reflectance at each pixel's angle:
// (1 - metallic) ((1 - T) x the glTF dielectric's albedo + T x the glass's Fresnel reflection)
// + metallic x the conductor's. Each stage samples the part chosen at the hit its own way.
// A transmissionTexture scales T per point (its R, linear): each half of a plane shows its own T.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <string>

#include "common/scene/scene_loading.h"
#include "tests/support/analytic_suite.h"
#include "tests/support/cli_run.h"
#include "tests/support/gltf_textured.h"
#include "tests/support/gltf_writer.h"
#include "tests/support/image_checks.h"
#include "tests/support/test_render.h"
#include "tests/support/texels.h"
#include "tests/support/texture_scenes.h"
#include "tests/support/transmission_mix.h"

using namespace pt;
using namespace pt::test;

namespace {

constexpr int kPlaneSize = 16;

// The plane of 200 x 200 at y = 0 facing up with `b`'s factors and transmission t, a black
// Lambert plane (specular 0) at y = -1 that takes whatever goes through, and a camera at
// (0, 1, 0) of yfov 60 degrees pitched 50 degrees down: every ray meets the plane between 20
// and 80 degrees below the horizon.
Scene transmissive_plane(const GltfBrdf& b, double t, const std::string& name) {
  GltfWriter g;
  int m = g.material({{"pbrMetallicRoughness",
                       {{"baseColorFactor", {b.base.x, b.base.y, b.base.z, 1.0}}, {"metallicFactor", b.metallic},
                        {"roughnessFactor", b.roughness}}},
                      {"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", t}}}}}});
  g.uses("KHR_materials_transmission");
  int black = g.diffuse(glm::vec3(0.0f));
  g.node({{"mesh", g.quad({-100, 0, 100}, {100, 0, 100}, {100, 0, -100}, {-100, 0, -100}, m)}});
  g.node({{"mesh", g.quad({-100, -1, 100}, {100, -1, 100}, {100, -1, -100}, {-100, -1, -100}, black)}});
  double half = -25.0 * M_PI / 180.0;  // a rotation of -50 degrees about x: -Z turns down
  g.node({{"camera", g.perspective(60.0 * M_PI / 180.0)},
          {"translation", {0, 1, 0}},
          {"rotation", {std::sin(half), 0, 0, std::cos(half)}}});
  return load_gltf(g.write(pt_test::scratch_dir("pt_transmission").string() + "/" + name + ".gltf"));
}

// The same plane with transmissionFactor `factor` and a transmissionTexture of 2 x 1 texels
// (NEAREST, clamped) over u = (x + 100) / 200: `left` for x < 0, `right` for x > 0. The
// camera sees x < 0 in the left half of the image, which kPlaneSize even splits between pixels.
Scene textured_plane(const GltfBrdf& b, double factor, uint left, uint right, const std::string& name) {
  GltfWriter g;
  int tex = image_texture(g, 2, 1, {left, right});
  int m = g.material({{"pbrMetallicRoughness",
                       {{"baseColorFactor", {b.base.x, b.base.y, b.base.z, 1.0}}, {"metallicFactor", b.metallic},
                        {"roughnessFactor", b.roughness}}},
                      {"extensions",
                       {{"KHR_materials_transmission",
                         {{"transmissionFactor", factor}, {"transmissionTexture", {{"index", tex}}}}}}}});
  g.uses("KHR_materials_transmission");
  int black = g.diffuse(glm::vec3(0.0f));
  g.node({{"mesh", textured_quad(g, {{-100, 0, 100}, {100, 0, 100}, {100, 0, -100}, {-100, 0, -100}},
                                 {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {}, m)}});
  g.node({{"mesh", g.quad({-100, -1, 100}, {100, -1, 100}, {100, -1, -100}, {-100, -1, -100}, black)}});
  double half = -25.0 * M_PI / 180.0;
  g.node({{"camera", g.perspective(60.0 * M_PI / 180.0)},
          {"translation", {0, 1, 0}},
          {"rotation", {std::sin(half), 0, 0, std::cos(half)}}});
  return load_gltf(g.write(pt_test::scratch_dir("pt_transmission").string() + "/" + name + ".gltf"));
}

// The image of the plane when a direction seen at cosine c from the normal has radiance
// `value(c)`.
ExpectedImage transmissive_plane_image(const Scene& scene, const std::function<glm::dvec3(double)>& value) {
  return expected_image_by_direction(scene, kPlaneSize, kPlaneSize, [&](glm::dvec3 dir) { return value(-dir.y); });
}

void check_plane(const GltfBrdf& b, double t, const std::string& name, std::uint32_t seed) {
  Scene scene = transmissive_plane(b, t, name);
  REQUIRE(scene.materials.at(0).kind == kMaterialDielectric);
  REQUIRE(scene.materials.at(0).transmission == float(t));
  MixtureTable table(b, t, 129);
  ExpectedImage want = transmissive_plane_image(scene, [&](double c) { return kSky * table.at(c); });
  for (const StageKernels& kernels : path_tracing_stages()) {
    INFO(kernels.name);
    RenderSettings s = settings(kPlaneSize, kPlaneSize, 64, seed += 100);
    s.sky = glm::vec3(kSky);
    // The tables' own error (midpoint rule, interpolation) is below 1e-3 of them.
    check_scene(kernels, scene, want, s, 1e-3);
  }
}

}  // namespace

TEST_CASE("transmission: a smooth white plane of transmission 0.5 over black shows the sky times half the "
          "dielectric's albedo plus half the Fresnel reflection, in stages 2 to 5",
          "[stage2][stage3][stage4][stage5][transmission][statistical]") {
  GltfBrdf b;
  b.base = {1.0, 1.0, 1.0}, b.roughness = 0.0;
  check_plane(b, 0.5, "smooth_half", test_seed(47200));
}

TEST_CASE("transmission: a rough tinted plane of transmission 0.2, metallic 0.3, over black shows the sky times "
          "the mixture's reflectance, in stages 2 to 5",
          "[stage2][stage3][stage4][stage5][transmission][statistical]") {
  GltfBrdf b;
  b.base = {0.8, 0.6, 0.4}, b.metallic = 0.3, b.roughness = 0.5;
  check_plane(b, 0.2, "rough_fifth", test_seed(47300));
}

TEST_CASE("transmissionTexture: a rough plane of transmissionFactor 1 whose texture's R is 128/255 on its left half "
          "and 0 on its right shows the mixture of transmission 128/255 there and the plain dielectric here, in "
          "stages 2 to 5",
          "[stage2][stage3][stage4][stage5][transmission][transmission_texture][statistical]") {
  GltfBrdf b;
  b.base = {0.9, 0.7, 0.5}, b.metallic = 0.3, b.roughness = 0.5;
  // G, B and A differ from R: only R (linear, not sRGB-decoded) scales the factor.
  Scene scene = textured_plane(b, 1.0, pt_test::rgba(128, 0, 255, 255), pt_test::rgba(0, 255, 255, 255), "textured");
  REQUIRE(scene.materials.at(0).kind == kMaterialDielectric);
  REQUIRE(scene.material_textures.at(0).transmission != kNoTexture);
  MixtureTable left(b, 128.0 / 255.0, 129), right(b, 0.0, 129);
  ExpectedImage want = expected_image_by_direction(
      scene, kPlaneSize, kPlaneSize, [&](glm::dvec3 dir) { return kSky * (dir.x < 0.0 ? left : right).at(-dir.y); });
  std::uint32_t seed = test_seed(47400);
  for (const StageKernels& kernels : path_tracing_stages()) {
    INFO(kernels.name);
    RenderSettings s = settings(kPlaneSize, kPlaneSize, 64, seed += 100);
    s.sky = glm::vec3(kSky);
    check_scene(kernels, scene, want, s, 1e-3);
  }
}
