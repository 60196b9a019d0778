// Textures and vertex colours in rendered images (issue #19; common/kernel/texture.glsl), on
// the backend under test (pt_tests: the CPU, pt_gpu_tests: Vulkan): white textures and
// white vertex colours change nothing, bit for bit, and a constant texture is its factor
// times its decoded texel. The textured plane under a uniform sky: test_texture_plane.cpp;
// emissive textures and alpha masks: test_texture_emissive_alpha.cpp.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "common/scene/analytic_scenes.h"
#include "common/scene/scene_loading.h"
#include "stage1_raycast/kernels.h"
#include "stage2_montecarlo/kernels.h"
#include "stage3_importance/kernels.h"
#include "stage4_direct_indirect/kernels.h"
#include "stage5_mis/kernels.h"
#include "tests/support/image_checks.h"
#include "tests/support/test_render.h"
#include "tests/support/texels.h"
#include "tests/support/texture_scenes.h"

using namespace pt;
using namespace pt::test;

namespace {

using pt_test::rgba;

// The Cornell box with a rough metal box and a mixed one; `textured`: every material reads
// white base colour, emissive and metallic-roughness textures (factors as the material's),
// and every triangle has white vertex colours and uv all over the textures.
Scene cornell_metals(bool textured) {
  Scene scene = make_builtin_scene("cornell");
  struct Factors {
    float metallic, roughness;
  };
  std::vector<Factors> factors(scene.materials.size(), Factors{0.0f, 1.0f});
  uint rough = scene.add_material(make_gltf_material({0.9f, 0.8f, 0.6f}, 1.0f, 0.4f, 0.0f, 1.5f, {}, false));
  uint mixed = scene.add_material(make_gltf_material({0.8f, 0.8f, 0.8f}, 0.3f, 0.2f, 0.0f, 1.5f, {}, false));
  factors.push_back({1.0f, 0.4f});
  factors.push_back({0.3f, 0.2f});
  std::size_t n = scene.triangles.size();
  for (std::size_t i = n - 24; i < n; i++) scene.triangles[i].material = i < n - 12 ? rough : mixed;
  if (textured) {
    scene.material_textures.assign(scene.materials.size(), no_material_textures());
    scene.triangle_attributes.assign(scene.triangles.size(), no_triangle_attributes());
    for (std::size_t i = 0; i < scene.materials.size(); i++) {
      MaterialTextures& mt = scene.material_textures[i];
      mt.base_color = 0u, mt.emissive = 1u, mt.metallic_roughness = 0u;
      mt.metallic_factor = factors[i].metallic, mt.roughness_factor = factors[i].roughness;
      mt.emissive_s = glm::vec3(3.0f, 0.5f, 0.25f);  // any transform: the texture is white
    }
    for (std::size_t i = 0; i < n; i++) {
      TriangleAttributes& a = scene.triangle_attributes[i];
      a.uv0 = glm::vec2(0.1f * float(i), -0.3f), a.uv1 = glm::vec2(2.5f, 0.7f), a.uv2 = glm::vec2(-1.2f, 5.1f);
    }
    uint white = rgba(255, 255, 255, 255);
    scene.textures.push_back(Texture{0u, 3u, 2u, kWrapRepeat, kWrapMirroredRepeat, kFilterLinear, white, white});
    scene.textures.push_back(Texture{0u, 2u, 1u, kWrapClampToEdge, kWrapRepeat, kFilterNearest, white, white});
    scene.texels.assign(6, white);
  }
  build_light_table(scene);
  return scene;
}

}  // namespace

TEST_CASE("textures: white textures and white vertex colours render the untextured image, in every stage",
          "[stage1][stage2][stage3][stage4][stage5][texture][features]") {
  const Scene plain = cornell_metals(false), textured = cornell_metals(true);
  REQUIRE((scene_feature_mask(textured, glm::vec3(0.0f)) & kFeatureTextures) != 0u);
  for (const StageKernels& kernels :
       {stage1::kernels(), stage2::kernels(), stage3::kernels(), stage4::kernels(), stage5::kernels()}) {
    RenderSettings s = settings(16, 16, 8, test_seed(19000));
    s.roulette = kRouletteThroughput;
    std::vector<float> a = render_on_test_backend(kernels, plain, s).film.mean_rgb();
    std::vector<float> b = render_on_test_backend(kernels, textured, s).film.mean_rgb();
    INFO(kernels.name);
    // A white texel is 1 exactly and multiplies nothing away; the CPU gives the same bits.
    // The Vulkan driver compiles the two specialisations apart and may fuse a multiply and
    // an add in one and not the other (tests/stages/test_specialised.cpp).
    CHECK(max_ulps(a, b) <= (backend_under_test == "cpu" ? 0u : 4u));
  }
}

TEST_CASE("textures: a constant texture equals its factor times its decoded texel", "[stage1][stage3][texture]") {
  // sRGB (128, 64, 200) everywhere against the untextured base colour factor x its decoding.
  Scene plain = sky_plane(), textured = sky_plane();
  const uint texel = rgba(128, 64, 200, 255);
  std::fill(textured.texels.begin(), textured.texels.end(), texel);
  auto decode = [](uint c) { return float(std::pow((float(c) / 255.0f + 0.055f) / 1.055f, 2.4f)); };
  plain.material_textures.clear(), plain.triangle_attributes.clear(), plain.textures.clear(), plain.texels.clear();
  plain.materials[0].base_color *= glm::vec3(decode(128), decode(64), decode(200));
  for (const StageKernels& kernels : {stage1::kernels(), stage3::kernels()}) {
    RenderSettings s = settings(16, 16, 16, test_seed(19100));
    s.sky = glm::vec3(kSky);
    std::vector<float> a = render_on_test_backend(kernels, plain, s).film.mean_rgb();
    std::vector<float> b = render_on_test_backend(kernels, textured, s).film.mean_rgb();
    INFO(kernels.name);
    // The same floats on the CPU, where pow is the one of the decoding above; to within
    // the GPU's pow (a few ulps of the albedo) on Vulkan.
    double worst = 0.0;
    for (std::size_t i = 0; i < a.size(); i++) worst = std::max(worst, double(std::abs(a[i] - b[i])) / std::max(1e-6f, a[i]));
    CHECK(worst <= (backend_under_test == "cpu" ? 0.0 : 1e-4));
  }
}
