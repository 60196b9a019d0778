// Textures and vertex colours in rendered images (issue #19; common/kernel/texture.glsl), on
// the backend under test (pt_tests: the CPU, pt_gpu_tests: Vulkan): white textures and
// white vertex colours change nothing, bit for bit; a textured plane under a uniform sky is
// albedo x texture x sky, pixel by pixel (nearest) and in the image mean (bilinear, a
// texture of known mean); COLOR_0 multiplies the base colour; and light sampling weighs a
// point on an emitter by its emissive texture (a two-tone light over a floor, Lambert's
// formula for each half). Tolerances come from the images' own variance (image_checks.h).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "common/scene/analytic_scenes.h"
#include "common/scene/scene_loading.h"
#include "stage1_raycast/kernels.h"
#include "stage2_montecarlo/kernels.h"
#include "stage3_importance/kernels.h"
#include "stage4_direct_indirect/kernels.h"
#include "stage5_mis/kernels.h"
#include "tests/support/analytic_suite.h"
#include "tests/support/image_checks.h"
#include "tests/support/lambert.h"
#include "tests/support/test_render.h"
#include "common/base/srgb.h"
#include "tests/support/texels.h"

using namespace pt;
using namespace pt::test;

namespace {

using pt_test::rgba;

// A texel's colour decoded from sRGB, in double.
glm::dvec3 srgb_texel(uint v) {
  return glm::dvec3(pt::srgb_to_linear((v & 255u) / 255.0), pt::srgb_to_linear((v >> 8 & 255u) / 255.0),
                    pt::srgb_to_linear((v >> 16 & 255u) / 255.0));
}

std::vector<StageKernels> path_tracing_stages() {
  return {stage2::kernels(), stage3::kernels(), stage4::kernels(), stage5::kernels()};
}

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

// The sky plane (tests/data/gltf/tex_sky_plane.gltf): a 2 x 2 quad filling an orthographic
// view, its 4 x 4 texture repeated twice over it (u = x + 1, v = 1 - y), nearest texels.
const glm::dvec3 kSky(0.5, 1.0, 2.0);
// Stages 3 to 5 sample the plane's one bounce by its cosine: every sample is the pixel's
// value up to float rounding (the film's variance is about 0), so the image means are
// compared with that rounding allowed (channel_means_ratio's relative floor).
const double kRounding = 1e-5;

Scene sky_plane() {
  return load_gltf(PT_SOURCE_DIR "/tests/data/gltf/tex_sky_plane.gltf");
}

// COLOR_0 at the plane's point (x, y): an affine function, so that the corners' colours
// interpolated over either triangle give it everywhere, and a pixel's mean is its centre's.
glm::dvec3 plane_color(double x, double y) {
  return glm::dvec3(0.6 + 0.3 * x, 0.5 - 0.4 * y, 0.7 + 0.1 * x + 0.2 * y);
}

// The sky plane's image at 16 x 16 pixels: each pixel lies within one texel (2 x 2 pixels a
// texel), so its value is factor x texel x sky (x the colour at its centre when `colored`).
ExpectedImage sky_plane_image(const Scene& scene, glm::dvec3 light, bool colored) {
  const Texture& t = scene.textures.at(0);
  const glm::dvec3 factor(scene.materials.at(0).base_color);
  return expected_image(16, 16, [&](double x0, double y0, double x1, double y1) {
    double x = 0.5 * (x0 + x1), y = 0.5 * (y0 + y1);
    uint tx = uint(std::floor(4.0 * (x + 1.0))) % 4u, ty = uint(std::floor(4.0 * (1.0 - y))) % 4u;
    glm::dvec3 v = factor * srgb_texel(scene.texels[t.offset + ty * t.width + tx]) * light;
    return colored ? v * plane_color(x, y) : v;
  });
}

void color_plane(Scene& scene) {
  const glm::vec2 corner[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};  // the quad's corners, triangles 012 and 023
  const int tris[2][3] = {{0, 1, 2}, {0, 2, 3}};
  for (int t = 0; t < 2; t++) {
    glm::vec4 c[3];
    for (int k = 0; k < 3; k++) {
      glm::vec2 p = corner[tris[t][k]];
      c[k] = glm::vec4(glm::vec3(plane_color(p.x, p.y)), 1.0f);
    }
    TriangleAttributes& a = scene.triangle_attributes.at(std::size_t(t));
    a.color0 = c[0], a.color1 = c[1], a.color2 = c[2];
  }
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

TEST_CASE("textures: stage1 shows a textured plane's base colour, texel by texel", "[stage1][texture]") {
  Scene scene = sky_plane();
  ExpectedImage want = sky_plane_image(scene, glm::dvec3(1.0), false);
  color_plane(scene);
  ExpectedImage colored = sky_plane_image(scene, glm::dvec3(1.0), true);
  for (bool with_colors : {false, true}) {
    Scene s = sky_plane();
    if (with_colors) color_plane(s);
    Film film = render_on_test_backend(stage1::kernels(), s, settings(16, 16, 16, test_seed(19200))).film;
    const ExpectedImage& expected = with_colors ? colored : want;
    INFO((with_colors ? "with" : "without") << " COLOR_0");
    // Nearest texels, one per pixel: every sample of a pixel sees its texel (a sample within
    // rounding of a texel's edge may see the next one: one pixel may be off by a sample's
    // share). COLOR_0 varies over a pixel: its 16 samples' mean is its centre's only within
    // their spread, a few percent.
    double worst = 0.0;
    int off = 0;
    for (int y = 0; y < 16; y++) {
      for (int x = 0; x < 16; x++) {
        glm::dvec3 got = film.mean(x, y), w = expected[std::size_t(y) * 16 + x];
        double error = glm::length(got - w) / glm::length(w);
        worst = std::max(worst, error);
        off += error > 1e-5;
      }
    }
    CHECK(worst <= (with_colors ? 0.05 : 0.1));
    if (!with_colors) CHECK(off <= 1);
  }
}

TEST_CASE("textures: a textured plane under a uniform sky is factor x texture x sky, in stages 2 to 5",
          "[texture][statistical]") {
  Scene nearest = sky_plane();
  ExpectedImage want = sky_plane_image(nearest, kSky, false);
  // Bilinear, repeated over whole periods: the image's mean is the texels' decoded mean.
  Scene bilinear = sky_plane();
  bilinear.textures[0].mag_filter = kFilterLinear;
  glm::dvec3 mean(0.0);
  for (uint v : bilinear.texels) mean += srgb_texel(v) / double(bilinear.texels.size());
  const ExpectedImage flat(16 * 16, glm::dvec3(bilinear.materials[0].base_color) * mean * kSky);
  std::uint32_t seed = test_seed(19300);
  for (const StageKernels& kernels : path_tracing_stages()) {
    INFO(kernels.name);
    RenderSettings s = settings(16, 16, 64, seed += 100);
    s.sky = glm::vec3(kSky);
    check_scene(kernels, nearest, want, s, kRounding);
    std::vector<Film> batches = render_batches(kernels, bilinear, s, 8);
    CHECK(channel_means_ratio(batches, flat, 1e-3, kRounding) <= 1.0);
  }
}

TEST_CASE("textures: COLOR_0 multiplies the base colour", "[stage2][stage4][texture][statistical]") {
  Scene scene = sky_plane();
  color_plane(scene);
  ExpectedImage want = sky_plane_image(scene, kSky, true);
  RenderSettings s = settings(16, 16, 64, test_seed(19400));
  s.sky = glm::vec3(kSky);
  for (const StageKernels& kernels : {stage2::kernels(), stage4::kernels()}) {
    INFO(kernels.name);
    check_scene(kernels, scene, want, s, kRounding);
  }
}

namespace {

// The floor under the square light of builtin:floor_light, the light's emissive texture
// two texels (nearest, clamped) across it: its x < 0 half emits Le x texel 0, its x > 0
// half Le x texel 1. Each half is a uniform polygon: Lambert's formula for each. With
// `left_hole` the light has an alpha mask and texel 0 alpha 0: its x < 0 half is a hole,
// which neither the BSDF's rays (stages 2, 3) nor the light samples (stages 4, 5) may find.
void check_light_halves(bool left_hole, std::uint32_t seed) {
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
  for (const StageKernels& kernels : path_tracing_stages()) {
    INFO(kernels.name);
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

TEST_CASE("alpha masks: a masked plane's holes show the sky behind, a fully masked occluder is not there, in every stage",
          "[stage1][stage2][texture][alpha_mask][statistical]") {
  // tests/data/gltf/tex_mask.gltf: the sky plane whose texels' alpha is a checkerboard of 0
  // and 1 (cutoff 0.5), behind a quad at z = 0.5 whose alpha 0.2 is below its cutoff 0.25
  // everywhere. Camera rays pass the occluder and the plane's holes; the plane's bounce and
  // shadow rays pass the occluder: the plane is factor x texel x sky as without it, its
  // holes the sky.
  const Scene scene = load_gltf(PT_SOURCE_DIR "/tests/data/gltf/tex_mask.gltf");
  REQUIRE((scene_feature_mask(scene, glm::vec3(kSky)) & kFeatureAlphaMask) != 0u);
  const Texture& t = scene.textures.at(0);
  const glm::dvec3 factor(scene.materials.at(0).base_color);
  auto image = [&](bool shaded) {
    return expected_image(16, 16, [&](double x0, double y0, double x1, double y1) {
      double x = 0.5 * (x0 + x1), y = 0.5 * (y0 + y1);
      uint tx = uint(std::floor(4.0 * (x + 1.0))) % 4u, ty = uint(std::floor(4.0 * (1.0 - y))) % 4u;
      uint v = scene.texels[t.offset + ty * t.width + tx];
      if ((v >> 24) == 0u) return kSky;  // a hole
      return factor * srgb_texel(v) * (shaded ? kSky : glm::dvec3(1.0));
    });
  };
  std::uint32_t seed = test_seed(19600);
  RenderSettings s = settings(16, 16, 32, seed);
  s.sky = glm::vec3(kSky);
  {
    INFO("stage1_raycast");
    s.seed = seed;
    check_scene(stage1::kernels(), scene, image(false), s, kRounding);
  }
  for (const StageKernels& kernels : path_tracing_stages()) {
    INFO(kernels.name);
    s.seed = seed += 100;
    check_scene(kernels, scene, image(true), s, kRounding);
  }
  // The control: with the occluder opaque the camera sees it instead (the test can fail).
  Scene opaque = scene;
  for (MaterialTextures& mt : opaque.material_textures) {
    if (mt.base_color == kNoTexture) mt.alpha_cutoff = 0.0f;
  }
  mark_alpha_masked(opaque);
  RenderResult r = render_on_test_backend(stage2::kernels(), opaque, s);
  glm::dvec3 want = image(true)[0], got = r.film.mean(0, 0);
  CHECK(std::abs(got.x - want.x) > 0.1 * want.x);
}
