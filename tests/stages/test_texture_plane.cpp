// Textures and vertex colours in rendered images (issue #19; common/kernel/texture.glsl), on
// the backend under test (pt_tests: the CPU, pt_gpu_tests: Vulkan): a textured plane under
// a uniform sky is albedo x texture x sky, pixel by pixel (nearest) and in the image mean
// (bilinear, a texture of known mean), and COLOR_0 multiplies the base colour. Tolerances
// come from the images' own variance (image_checks.h).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

#include "stage1_raycast/kernels.h"
#include "stage2_montecarlo/kernels.h"
#include "stage4_direct_indirect/kernels.h"
#include "tests/support/analytic_suite.h"
#include "tests/support/image_checks.h"
#include "tests/support/test_render.h"
#include "tests/support/texture_scenes.h"

using namespace pt;
using namespace pt::test;

namespace {

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
