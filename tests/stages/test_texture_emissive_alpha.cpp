// Emissive textures and alpha masks in rendered images (issue #19; common/kernel/texture.glsl),
// on the backend under test (pt_tests: the CPU, pt_gpu_tests: Vulkan): light sampling
// weighs a point on an emitter by its emissive texture (a two-tone light over a floor,
// Lambert's formula for each half; read through TEXCOORD_0 or TEXCOORD_1), an emitter's
// holes emit nothing, and a masked plane's holes show the sky behind it. Tolerances come
// from the images' own variance (image_checks.h).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

#include "common/scene/analytic_scenes.h"
#include "common/scene/scene_loading.h"
#include "stage1_raycast/kernels.h"
#include "stage2_montecarlo/kernels.h"
#include "stage5_mis/kernels.h"
#include "tests/support/analytic_suite.h"
#include "tests/support/image_checks.h"
#include "tests/support/lambert.h"
#include "tests/support/test_render.h"
#include "tests/support/texels.h"
#include "tests/support/texture_scenes.h"

using namespace pt;
using namespace pt::test;

namespace {

using pt_test::rgba;

// The floor under the square light of builtin:floor_light, the light's emissive texture
// two texels (nearest, clamped) across it: its x < 0 half emits Le x texel 0, its x > 0
// half Le x texel 1. Each half is a uniform polygon: Lambert's formula for each. With
// `left_hole` the light has an alpha mask and texel 0 alpha 0: its x < 0 half is a hole,
// which neither the BSDF's rays (stages 2, 3) nor the light samples (stages 4, 5) may find.
// With `set1` the textures read TEXCOORD_1 (kSlot* bits), which holds that layout, while
// TEXCOORD_0 holds it mirrored (u -> 1 - u, the halves swapped), in stage5 only: its light
// samples and its BSDF rays that hit the light both count (MIS), and every stage reads a
// texture through the same texture.glsl, so the other stages would run that code again
// at three times the cost (issue #51; a set read wrongly swaps the halves, far beyond the noise).
void check_light_halves(bool left_hole, std::uint32_t seed, bool set1 = false) {
  analytic::FloorLightScene a;
  Scene scene = analytic::make_floor_light(a);
  const uint t0 = rgba(255, 200, 100, left_hole ? 0 : 255), t1 = rgba(30, 60, 255, 255);
  scene.material_textures.assign(scene.materials.size(), no_material_textures());
  scene.triangle_attributes.assign(scene.triangles.size(), no_triangle_attributes());
  scene.textures.push_back(Texture{0u, 2u, 1u, kWrapClampToEdge, kWrapClampToEdge, kFilterNearest, 0u, 0u});
  scene.texels = {t0, t1};
  const uint light = scene.triangles.back().material;
  scene.material_textures[light].emissive = 0u;
  if (left_hole) {
    scene.material_textures[light].base_color = 0u;  // its alpha: the mask
    scene.material_textures[light].alpha_cutoff = 0.5f;
  }
  // The light's triangles (-l,-l) (l,-l) (l,l) and (-l,-l) (l,l) (-l,l) in x, z: u = (x / l + 1) / 2.
  std::size_t n = scene.triangles.size();
  scene.triangle_attributes[n - 2].uv0 = {0, 0}, scene.triangle_attributes[n - 2].uv1 = {1, 0};
  scene.triangle_attributes[n - 2].uv2 = {1, 1};
  scene.triangle_attributes[n - 1].uv0 = {0, 0}, scene.triangle_attributes[n - 1].uv1 = {1, 1};
  scene.triangle_attributes[n - 1].uv2 = {0, 1};
  if (set1) {
    for (std::size_t t : {n - 2, n - 1}) {
      TriangleAttributes& a = scene.triangle_attributes[t];
      a.set1_uv0 = a.uv0, a.set1_uv1 = a.uv1, a.set1_uv2 = a.uv2;
      a.uv0.x = 1.0f - a.uv0.x, a.uv1.x = 1.0f - a.uv1.x, a.uv2.x = 1.0f - a.uv2.x;
    }
    scene.material_textures[light].tex_coord_sets = (1u << kSlotEmissive) | (1u << kSlotBaseColor);
  }
  mark_alpha_masked(scene);
  build_light_table(scene);
  REQUIRE(uses_alpha_mask(scene) == left_hole);
  const glm::dvec3 e0 = left_hole ? glm::dvec3(0.0) : glm::dvec3(a.emission) * srgb_texel(t0);
  const glm::dvec3 e1 = glm::dvec3(a.emission) * srgb_texel(t1);
  struct Halves {
    analytic::FloorLightScene a;
    glm::dvec3 e0, e1;
    int channel;
  };
  const int size = 20;
  ExpectedImage want = expected_image(size, size, [&](double x0, double y0, double x1, double y1) {
    glm::dvec3 v;
    for (int c = 0; c < 3; c++) {
      Halves h{a, e0, e1, c};
      auto radiance = [](double sx, double sy, const void* data) {
        const Halves& h = *static_cast<const Halves*>(data);
        double l = h.a.light_half, y = h.a.light_height;
        glm::dvec3 p(sx * h.a.view_half, 0.0, -sy * h.a.view_half);
        double left = polygon_irradiance({{-l, y, -l}, {0, y, -l}, {0, y, l}, {-l, y, l}}, p, {0, 1, 0}, h.e0[h.channel]);
        double right = polygon_irradiance({{0, y, -l}, {l, y, -l}, {l, y, l}, {0, y, l}}, p, {0, 1, 0}, h.e1[h.channel]);
        return h.a.albedo / M_PI * (left + right);
      };
      v[c] = rect_average(x0, y0, x1, y1, radiance, &h);
    }
    return v;
  });
  for (const StageKernels& kernels : set1 ? std::vector<StageKernels>{stage5::kernels()} : path_tracing_stages()) {
    INFO(kernels.name);
    if (backend_under_test == "gpu") {
      // On the GPU: the CPU's image to rounding, sample for sample, at 64 spp, 1/128 of
      // the closed form's samples (issue #51: these were the longest tests on lavapipe).
      // The CPU's run of this test holds the closed form; a GPU that weighed a light
      // sample without its texel or missed the hole fails here (tried: docs/testing.md).
      const RenderSettings s = settings(size, size, 64, seed += 100);
      const Film cpu = render_on("cpu", kernels, scene, s).film, gpu = render_on("gpu", kernels, scene, s).film;
      CHECK(agreeing_fraction(cpu, gpu) >= 0.999);
      CHECK(agreeing_squares_fraction(cpu, gpu) >= 0.999);
      continue;
    }
    check_scene(kernels, scene, want, settings(size, size, 1024, seed += 100));
  }
}

}  // namespace

TEST_CASE("textures: light sampling weighs a point on an emitter by its emissive texture, in stages 2 to 5",
          "[texture][statistical]") {
  check_light_halves(false, test_seed(19500));
}

TEST_CASE("alpha masks: an emitter's holes emit nothing, for light samples and BSDF rays alike, in stages 2 to 5",
          "[texture][alpha_mask][statistical]") {
  check_light_halves(true, test_seed(19700));
}

TEST_CASE("texCoord 1: light sampling and BSDF rays weigh an emitter by its emissive texture and cut its holes "
          "through TEXCOORD_1, in stage5",
          "[texture][texcoord][alpha_mask][statistical]") {
  check_light_halves(false, test_seed(47300), true);
  check_light_halves(true, test_seed(47400), true);
}

namespace {

// tests/data/gltf/tex_mask.gltf: the sky plane whose texels' alpha is a checkerboard of 0 and
// 1 (cutoff 0.5), behind a quad at z = 0.5 whose alpha 0.2 is below its cutoff 0.25
// everywhere. Camera rays pass the occluder and the plane's holes; the plane's bounce and
// shadow rays pass the occluder: the plane is factor x texel x sky as without it, its holes
// the sky (stage1: factor x texel).
struct MaskedPlane {
  Scene scene = load_gltf(PT_SOURCE_DIR "/tests/data/gltf/tex_mask.gltf");
  ExpectedImage image(bool shaded) const {
    const Texture& t = scene.textures.at(0);
    const glm::dvec3 factor(scene.materials.at(0).base_color);
    return expected_image(16, 16, [&](double x0, double y0, double x1, double y1) {
      double x = 0.5 * (x0 + x1), y = 0.5 * (y0 + y1);
      uint tx = uint(std::floor(4.0 * (x + 1.0))) % 4u, ty = uint(std::floor(4.0 * (1.0 - y))) % 4u;
      uint v = scene.texels[t.offset + ty * t.width + tx];
      if ((v >> 24) == 0u) return kSky;  // a hole
      return factor * srgb_texel(v) * (shaded ? kSky : glm::dvec3(1.0));
    });
  }
};

}  // namespace

// Stages 1 and 2 in one test, stages 3 to 5 in another: a test of a stage's group carries the
// tag of every stage it runs (tests/test_main.cpp), and this texture test is not in the
// groups of stages 3 to 5 (docs/testing.md, section 8).
TEST_CASE("alpha masks: a masked plane's holes show the sky behind, a fully masked occluder is not there, in stages 1 "
          "and 2",
          "[stage1][stage2][texture][alpha_mask][statistical]") {
  const MaskedPlane plane;
  REQUIRE((scene_feature_mask(plane.scene, glm::vec3(kSky)) & kFeatureAlphaMask) != 0u);
  std::uint32_t seed = test_seed(19600);
  RenderSettings s = settings_under_sky(16, 16, 32, seed);
  {
    INFO("stage1_raycast");
    check_scene(stage1::kernels(), plane.scene, plane.image(false), s, kRounding);
  }
  {
    INFO("stage2_montecarlo");
    s.seed = seed + 100;
    check_scene(stage2::kernels(), plane.scene, plane.image(true), s, kRounding);
  }
  // The control: with the occluder opaque the camera sees it instead (the test can fail).
  Scene opaque = plane.scene;
  for (MaterialTextures& mt : opaque.material_textures) {
    if (mt.base_color == kNoTexture) mt.alpha_cutoff = 0.0f;
  }
  mark_alpha_masked(opaque);
  s.seed = seed + 400;  // the seed the control had after the loop over stages 2 to 5
  RenderResult r = render_on_test_backend(stage2::kernels(), opaque, s);
  glm::dvec3 want = plane.image(true)[0], got = r.film.mean(0, 0);
  CHECK(std::abs(got.x - want.x) > 0.1 * want.x);
}

TEST_CASE("alpha masks: a masked plane's holes show the sky behind, a fully masked occluder is not there, in stages 3 "
          "to 5",
          "[texture][alpha_mask][statistical]") {
  const MaskedPlane plane;
  std::uint32_t seed = test_seed(19600) + 100;  // stage2's, in the test above
  RenderSettings s = settings_under_sky(16, 16, 32, seed);
  for (const StageKernels& kernels : {stage3::kernels(), stage4::kernels(), stage5::kernels()}) {
    INFO(kernels.name);
    s.seed = seed += 100;
    check_scene(kernels, plane.scene, plane.image(true), s, kRounding);
  }
}
