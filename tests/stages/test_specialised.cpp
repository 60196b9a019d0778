// Specialised kernels (issue "model only what a scene requires"): every stage's kernel
// built for exactly the features a scene uses (GPU: a specialization constant; CPU: the
// smallest compiled variant) renders the same image as the general kernel
// (--all-features). Runs on both backends (pt_tests: CPU, pt_gpu_tests: Vulkan).
//
// Where each part is checked. The gates that specialisation turns off (has_feature(), all
// in the shared kernel code, common/kernel/ and stage6's roulette) are the same source on
// both backends. The Release build's CPU copies are coarse (cpu_variants.h: the Cornell
// box's and the general one), but the check build's one CPU copy reads the feature set at
// run time (PT_CPU_RUNTIME_FEATURES, cpu/kernel_bindings.h), so there every case below
// runs each gate of stages 1-4 at exactly the GPU's mask, bit for bit. On the GPU a case
// costs the driver a compile of its own for each stage, most of this file's time there
// (issue #51; on lavapipe under the sanitizers, a cold cache: stage1's kernels 28 s,
// stage4's 172 s, docs/results/test_cost.csv). There stage1 runs every case: it checks
// that the mask the host passes as the specialization constant is the scene's, which is
// the same code for every stage. Every stage's specialised GPU kernels (the GPU's default)
// are checked besides, scene by scene, against the CPU's images (tests/gpu/
// test_cpu_gpu_agree.cpp) and the closed forms (the image tests in pt_gpu_tests).

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

#include "cpu/cpu_variants.h"
#include "common/scene/scene_loading.h"
#include "stage1_raycast/kernels.h"
#include "stage2_montecarlo/kernels.h"
#include "stage3_importance/kernels.h"
#include "stage4_direct_indirect/kernels.h"
#include "tests/support/image_checks.h"
#include "tests/support/test_render.h"

using namespace pt;

namespace {

struct Case {
  const char* scene;
  glm::vec3 sky;
};

// Between them, every feature: shapes, each material kind, each light kind and the sky.
const Case kCases[] = {
    {"builtin:cornell", glm::vec3(0.0f)},
    {"builtin:sphere", glm::vec3(0.7f, 0.8f, 1.0f)},
    {"builtin:mirror", glm::vec3(0.0f)},
    {"builtin:glass_slab", glm::vec3(0.0f)},
    {"builtin:furnace_sphere", glm::vec3(0.0f)},
    {"builtin:point_in_sphere", glm::vec3(0.0f)},
    {PT_SOURCE_DIR "/scenes/glossy_glass.gltf", glm::vec3(0.2f)},
    {"mixed", glm::vec3(0.0f)},  // the Cornell box with mixed materials, below
    {"gltf", glm::vec3(0.0f)},   // the Cornell box with glTF files' materials, below
    {"transmission", glm::vec3(0.0f)},  // its boxes with transmission between 0 and 1, below
    {PT_SOURCE_DIR "/tests/data/gltf/tex_seed.glb", glm::vec3(0.3f)},  // textures, vertex colours
    {PT_SOURCE_DIR "/tests/data/gltf/tex_mask.gltf", glm::vec3(0.3f)},  // alpha masks
    {"builtin:every_feature", glm::vec3(0.1f)},  // shading normals, with everything else
    {"environment", glm::vec3(0.0f)},  // the diffuse sphere under an environment map, below
};

// builtin:sphere under a small environment map (common/scene/environment.h): a sky
// gradient with one bright texel, turned by 30 degrees.
Scene environment_case() {
  Scene scene = make_builtin_scene("sphere");
  const uint w = 16, h = 8;
  std::vector<float> rgb(3 * w * h);
  for (uint i = 0; i < w * h; i++) {
    const float up = 1.0f - float(i / w) / float(h);
    rgb[3 * i] = 0.2f * up, rgb[3 * i + 1] = 0.3f * up, rgb[3 * i + 2] = 0.5f * up;
  }
  for (int c = 0; c < 3; c++) rgb[3 * (2 * w + 11) + c] = 40.0f;
  scene.environment = make_environment("gradient", w, h, rgb, 1.0f, 30.0f);
  return scene;
}

// The Cornell box whose boxes have glTF files' materials: the short one a rough dielectric
// mixed with metal, the tall one a smooth dielectric (a delta layer over its base); and a
// rough glass sphere (KHR_materials_transmission with roughness).
Scene gltf_case() {
  Scene scene = make_builtin_scene("cornell");
  GltfPbr rough, smooth;
  rough.base = {0.9f, 0.5f, 0.3f}, rough.metallic = 0.3f, rough.roughness = 0.4f;
  smooth.base = {0.6f, 0.7f, 0.8f}, smooth.metallic = 0.0f, smooth.roughness = 0.0f;
  uint r = scene.add_material(make_gltf_pbr_material(rough)), s = scene.add_material(make_gltf_pbr_material(smooth));
  std::size_t n = scene.triangles.size();
  for (std::size_t i = n - 24; i < n; i++) scene.triangles[i].material = i < n - 12 ? r : s;
  scene.add_sphere({-0.1f, 0.2f, 0.5f}, 0.2f, scene.add_material(make_rough_glass(glm::vec3(1.0f), 1.5f, 0.3f)));
  return scene;
}

// The Cornell box whose boxes have transmission between 0 and 1 (docs/gltf_material.md,
// "Partial transmission"): the short one rough (its glass part rough glass), metallic 0.2,
// the tall one smooth (smooth glass); the scene has no other glass, so only the mask's
// glass part bits let the specialised kernels draw them.
Scene transmission_case() {
  Scene scene = make_builtin_scene("cornell");
  GltfPbr rough, smooth;
  rough.base = {0.9f, 0.6f, 0.4f}, rough.metallic = 0.2f, rough.roughness = 0.4f, rough.transmission = 0.5f;
  smooth.base = {0.7f, 0.8f, 0.9f}, smooth.metallic = 0.0f, smooth.roughness = 0.0f, smooth.transmission = 0.3f;
  uint r = scene.add_material(make_gltf_pbr_material(rough)), s = scene.add_material(make_gltf_pbr_material(smooth));
  std::size_t n = scene.triangles.size();
  for (std::size_t i = n - 24; i < n; i++) scene.triangles[i].material = i < n - 12 ? r : s;
  return scene;
}

Scene load_case(const Case& c) {
  if (std::strcmp(c.scene, "gltf") == 0) return gltf_case();
  if (std::strcmp(c.scene, "transmission") == 0) return transmission_case();
  if (std::strcmp(c.scene, "environment") == 0) return environment_case();
  if (std::strcmp(c.scene, "mixed") != 0) return load_scene(c.scene);
  Scene scene = make_builtin_scene("cornell");
  // The boxes (the last 24 triangles): the short one a mix of rough metal and diffuse,
  // the tall one a mix of mirror and diffuse.
  uint rough = scene.add_material(make_gltf_material({0.9f, 0.8f, 0.6f}, 0.5f, 0.4f, 0.0f, 1.5f, {}, false));
  uint smooth = scene.add_material(make_gltf_material({0.8f, 0.8f, 0.8f}, 0.3f, 0.0f, 0.0f, 1.5f, {}, false));
  std::size_t n = scene.triangles.size();
  for (std::size_t i = n - 24; i < n; i++) scene.triangles[i].material = i < n - 12 ? rough : smooth;
  return scene;
}

}  // namespace

TEST_CASE("specialised and general kernels give identical images", "[stage1][stage2][stage3][stage4][features]") {
  uint all_features_seen = 0u;
  for (const Case& c : kCases) {
    Scene scene = load_case(c);
    all_features_seen |= scene_feature_mask(scene, c.sky);
    std::vector<StageKernels> stages = {stage1::kernels(), stage2::kernels(), stage3::kernels(), stage4::kernels()};
    if (test::backend_under_test != "cpu") stages = {stage1::kernels()};  // above: one compile per case and stage
    for (const StageKernels& kernels : stages) {
      RenderSettings s = test::settings(24, 24, 8, 7);
      s.sky = c.sky;
      s.roulette = kRouletteThroughput;
      std::vector<float> specialised = test::render_on_test_backend(kernels, scene, s).film.mean_rgb();
      s.all_features = true;
      std::vector<float> general = test::render_on_test_backend(kernels, scene, s).film.mean_rgb();
      INFO(kernels.name << ", scene " << c.scene << " [" << scene_features(scene, c.sky) << "]");
      // The CPU runs the same C++ either way: bit for bit. The Vulkan driver compiles each
      // specialisation on its own and may fuse a*b+c into one rounding in one and not the
      // other (GLSL allows it): a few values then differ in the last bit or two. A path
      // that went another way (a changed decision) would differ by far more.
      std::uint32_t allowed = test::backend_under_test == "cpu" ? 0u : 4u;
      CHECK(pt::test::max_ulps(specialised, general) <= allowed);
    }
  }
  CHECK(all_features_seen == kFeatureAll);  // the cases cover every feature
}
