// The glTF metallic-roughness material in rendered images (issue #46; docs/gltf_material.md),
// on the backend under test (pt_tests: the CPU, pt_gpu_tests: Vulkan), read from a glTF
// file: a plane under a uniform sky, seen in perspective so that each pixel sees it at its
// own angle, reflects the sky times the material's directional albedo there: the Fresnel
// reflectance of Appendix B's formula for a smooth black dielectric, Schlick's with F0 = base
// colour for a smooth metal, the numerically integrated albedo for a rough mix. Each stage
// samples the material its own way (stage2 uniformly, stage3 by the layer choice, stages 4
// and 5 with light samples of the sky). Tolerances come from the images' own variance.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <string>

#include "common/scene/scene_loading.h"
#include "tests/support/analytic_suite.h"
#include "tests/support/cli_run.h"
#include "tests/support/gltf_brdf.h"
#include "tests/support/gltf_writer.h"
#include "tests/support/image_checks.h"
#include "tests/support/test_render.h"
#include "tests/support/texture_scenes.h"

using namespace pt;
using namespace pt::test;

namespace test_gltf_material_images {  // this file's names: the unity build compiles it with others (tests/CMakeLists.txt)

namespace {

constexpr int kSize = 16;

// A plane of 200 x 200 at y = 0 facing up, seen from (0, 1, 0) by a camera of yfov 60 degrees
// pitched 50 degrees down: every ray meets the plane, between 20 and 80 degrees below the
// horizon. `material` as glTF spells it.
Scene sky_plane_with(const GltfWriter::Json& material, const std::string& name) {
  GltfWriter g;
  int m = g.material(material);
  g.node({{"mesh", g.quad({-100, 0, 100}, {100, 0, 100}, {100, 0, -100}, {-100, 0, -100}, m)}});
  double half = -25.0 * M_PI / 180.0;  // a rotation of -50 degrees about x: -Z turns down
  g.node({{"camera", g.perspective(60.0 * M_PI / 180.0)},
          {"translation", {0, 1, 0}},
          {"rotation", {std::sin(half), 0, 0, std::cos(half)}}});
  return load_gltf(g.write(pt_test::scratch_dir("pt_gltf_material").string() + "/" + name + ".gltf"));
}

GltfWriter::Json pbr(glm::vec3 base, double metallic, double roughness) {
  return {{"pbrMetallicRoughness",
           {{"baseColorFactor", {base.x, base.y, base.z, 1.0}}, {"metallicFactor", metallic},
            {"roughnessFactor", roughness}}}};
}

// The image of the plane when a direction seen at cosine c from the normal has radiance
// `value(c)`.
ExpectedImage plane_image(const Scene& scene, const std::function<glm::dvec3(double)>& value) {
  return expected_image_by_direction(scene, kSize, kSize, [&](glm::dvec3 dir) { return value(-dir.y); });
}

RenderSettings sky_settings(std::uint32_t seed) { return settings_under_sky(kSize, kSize, 64, seed); }

}  // namespace

TEST_CASE("glTF material: a smooth black dielectric under a uniform sky reflects Schlick's Fresnel with F0 0.04, "
          "pixel by pixel, in stages 2 to 5",
          "[stage2][stage3][stage4][stage5][gltf_material][statistical]") {
  Scene scene = sky_plane_with(pbr(glm::vec3(0.0f), 0.0, 0.0), "black_dielectric");
  REQUIRE(scene.materials.at(0).kind == kMaterialDielectric);
  ExpectedImage want = plane_image(scene, [](double c) { return kSky * (0.04 + 0.96 * std::pow(1.0 - c, 5.0)); });
  std::uint32_t seed = test_seed(46200);
  for (const StageKernels& kernels : path_tracing_stages()) {
    INFO(kernels.name);
    // Every sample of a pixel is exact up to rounding (the layer is the only lobe, a delta):
    // the pixel's spread is its angles' spread, which the film's variance estimates.
    check_scene(kernels, scene, want, sky_settings(seed += 100), kRounding);
  }
}

TEST_CASE("glTF material: a smooth metal is a mirror of its base colour (Schlick, F0 = base), in stages 2 to 5",
          "[stage2][stage3][stage4][stage5][gltf_material][statistical]") {
  const glm::dvec3 base(0.9, 0.6, 0.3);
  Scene scene = sky_plane_with(pbr(glm::vec3(base), 1.0, 0.0), "smooth_metal");
  REQUIRE(scene.materials.at(0).kind == kMaterialMirror);
  ExpectedImage want = plane_image(scene, [&](double c) { return kSky * gltf_schlick(base, c); });
  std::uint32_t seed = test_seed(46300);
  for (const StageKernels& kernels : path_tracing_stages()) {
    INFO(kernels.name);
    check_scene(kernels, scene, want, sky_settings(seed += 100), kRounding);
  }
}

TEST_CASE("glTF material: a rough dielectric-metal mix under a uniform sky is the sky times its integrated "
          "directional albedo, in stages 2 to 5",
          "[stage2][stage3][stage4][stage5][gltf_material][statistical]") {
  GltfBrdf b;
  b.base = {0.7, 0.4, 0.2}, b.metallic = 0.3, b.roughness = 0.5;
  GltfWriter::Json material = pbr(glm::vec3(b.base), b.metallic, b.roughness);
  // A tinted, weaker layer of a denser dielectric: KHR_materials_ior and _specular.
  b.ior = 1.7, b.specular = 0.8, b.specular_color = {1.0, 0.8, 0.6};
  material["extensions"] = {{"KHR_materials_ior", {{"ior", b.ior}}},
                            {"KHR_materials_specular", {{"specularFactor", b.specular},
                                                        {"specularColorFactor", {1.0, 0.8, 0.6}}}}};
  Scene scene = sky_plane_with(material, "rough_mix");
  REQUIRE(scene.materials.at(0).kind == kMaterialDielectric);
  AlbedoTable albedo(b, 129);
  ExpectedImage want = plane_image(scene, [&](double c) { return kSky * albedo.at(c); });
  std::uint32_t seed = test_seed(46400);
  for (const StageKernels& kernels : path_tracing_stages()) {
    INFO(kernels.name);
    // The albedo table's own error (midpoint rule, interpolation) is below 1e-3 of it.
    check_scene(kernels, scene, want, sky_settings(seed += 100), 1e-3);
  }
}

}  // namespace test_gltf_material_images
