// Textures on TEXCOORD_1 and KHR_materials_specular's textures in rendered images (issue #46;
// common/kernel/texture.glsl, texture_lookup.glsl slot_uv), on the backend under test
// (pt_tests: the CPU, pt_gpu_tests: Vulkan), from glTF files the tests write: each quad's
// TEXCOORD_0 points at one texel everywhere, so an image that shows the texture through
// TEXCOORD_1's layout shows that set was read. Closed forms: stage1's base colour and
// emission, a Lambert plane under a uniform sky (albedo x sky), a smooth metal (Schlick), and
// the dielectric's numerically integrated albedo (tests/support/gltf_brdf.h).
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "common/scene/scene_loading.h"
#include "stage1_raycast/kernels.h"
#include "tests/support/analytic_suite.h"
#include "tests/support/cli_run.h"
#include "tests/support/gltf_brdf.h"
#include "tests/support/gltf_textured.h"
#include "tests/support/image_checks.h"
#include "tests/support/texels.h"
#include "tests/support/texture_scenes.h"

using namespace pt;
using namespace pt::test;
using pt_test::rgba;

namespace {

constexpr int kTexcoordSize = 16;

// The 4 x 4 texture the plane shows on TEXCOORD_1 (u = (x + 1) / 2, v = (1 - y) / 2: each
// texel 4 x 4 pixels); TEXCOORD_0 is (0.9, 0.9) at every corner: texel (3, 3) everywhere.
// Alpha: 0 where `holes` and (tx + ty) is odd.
std::vector<uint> checker(bool holes) {
  std::vector<uint> t;
  for (uint ty = 0; ty < 4; ty++) {
    for (uint tx = 0; tx < 4; tx++) {
      uint a = holes && (tx + ty) % 2 ? 0u : 255u;
      t.push_back(rgba(40 + 60 * tx, 230 - 50 * ty, 90 + 30 * ((tx + ty) % 3), a));
    }
  }
  return t;
}

// The plane z = 0 over [-1, 1]^2 facing +z, seen straight on by an orthographic camera that
// it fills; `material` writes its material (and the textures it uses) into the file.
Scene plane_file(const std::string& name, const std::function<GltfWriter::Json(GltfWriter&)>& material) {
  GltfWriter g;
  GltfWriter::Json m = material(g);
  const glm::vec2 same(0.9f, 0.9f);
  g.node({{"mesh", textured_quad(g, {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}}, {same, same, same, same},
                                 {{0, 1}, {1, 1}, {1, 0}, {0, 0}}, g.material(m))}});
  orthographic_camera(g, {0, 0, 1});
  return load_gltf(g.write(pt_test::scratch_dir("pt_texcoord_images").string() + "/" + name + ".gltf"));
}

// A pixel's texel of checker(): its centre's.
uint pixel_texel(const std::vector<uint>& t, double x0, double y0, double x1, double y1) {
  double x = 0.5 * (x0 + x1), y = 0.5 * (y0 + y1);
  uint tx = std::min(3u, uint(std::floor(2.0 * (x + 1.0)))), ty = std::min(3u, uint(std::floor(2.0 * (1.0 - y))));
  return t[ty * 4 + tx];
}

// stage1's image against `want`, sample by sample exact (nearest texels, one per pixel; a
// sample within rounding of a texel's edge may see the next one: one pixel may be off).
void check_stage1(const Scene& scene, const ExpectedImage& want, std::uint32_t seed) {
  INFO("stage1_raycast");
  Film film = render_on_test_backend(stage1::kernels(), scene, settings(kTexcoordSize, kTexcoordSize, 16, seed)).film;
  int off = 0;
  for (int y = 0; y < kTexcoordSize; y++) {
    for (int x = 0; x < kTexcoordSize; x++) {
      glm::dvec3 got = film.mean(x, y), w = want[std::size_t(y) * kTexcoordSize + x];
      off += glm::length(got - w) > 1e-5 * glm::length(w);
    }
  }
  CHECK(off <= 1);
}

RenderSettings texcoord_sky_settings(std::uint32_t seed) { return settings_under_sky(kTexcoordSize, kTexcoordSize, 64, seed); }

// A Lambert material (metallic 0, no specular layer) of base colour `base`.
GltfWriter::Json lambert(glm::vec3 base) {
  return {{"pbrMetallicRoughness", {{"baseColorFactor", {base.x, base.y, base.z, 1.0}}, {"metallicFactor", 0.0}}},
          {"extensions", {{"KHR_materials_specular", {{"specularFactor", 0.0}}}}}};
}

// The base colour texture's plane and its image lit by `light`: factor x texel x light.
struct BaseColourPlane {
  std::vector<uint> texels = checker(false);
  glm::vec3 factor{0.9f, 0.8f, 0.7f};
  Scene scene = plane_file("base_colour", [this](GltfWriter& g) {
    GltfWriter::Json m = lambert(factor);
    m["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", image_texture(g, 4, 4, texels)}, {"texCoord", 1}};
    return m;
  });
  ExpectedImage image(glm::dvec3 light) const {
    return expected_image(kTexcoordSize, kTexcoordSize, [&](double x0, double y0, double x1, double y1) {
      return glm::dvec3(factor) * srgb_texel(pixel_texel(texels, x0, y0, x1, y1)) * light;
    });
  }
};

// The emissive texture's plane and its image.
struct EmissivePlane {
  std::vector<uint> texels = checker(false);
  Scene scene = plane_file("emissive", [this](GltfWriter& g) {
    GltfWriter::Json m = lambert(glm::vec3(0.0f));
    m["emissiveFactor"] = {1.0, 0.5, 0.25};
    m["emissiveTexture"] = {{"index", image_texture(g, 4, 4, texels)}, {"texCoord", 1}};
    return m;
  });
  ExpectedImage image() const {
    return expected_image(kTexcoordSize, kTexcoordSize, [&](double x0, double y0, double x1, double y1) {
      return glm::dvec3(1.0, 0.5, 0.25) * srgb_texel(pixel_texel(texels, x0, y0, x1, y1));
    });
  }
};

}  // namespace

// Each picture is checked in stage1 by one test and in stages 2 to 5 by another: a test of a
// stage's group carries the tag of every stage it runs (tests/test_main.cpp), and these
// texture tests are not in the groups of stages 2 to 5 (docs/testing.md, section 8).
TEST_CASE("texCoord 1: a base colour texture on TEXCOORD_1 is read through it: stage1 shows it texel by texel",
          "[stage1][texture][texcoord][statistical]") {
  const BaseColourPlane plane;
  check_stage1(plane.scene, plane.image(glm::dvec3(1.0)), test_seed(46700));
}

TEST_CASE("texCoord 1: a base colour texture on TEXCOORD_1 is read through it: stages 2 to 5 show the Lambert plane "
          "factor x texel x sky",
          "[texture][texcoord][statistical]") {
  const BaseColourPlane plane;
  std::uint32_t seed = test_seed(46700);
  for (const StageKernels& kernels : path_tracing_stages()) {
    INFO(kernels.name);
    check_scene(kernels, plane.scene, plane.image(kSky), texcoord_sky_settings(seed += 100), kRounding);
  }
}

TEST_CASE("texCoord 1: an emissive texture on TEXCOORD_1 is seen through it, in stage1",
          "[stage1][texture][texcoord][statistical]") {
  const EmissivePlane plane;
  check_stage1(plane.scene, plane.image(), test_seed(46800));
}

TEST_CASE("texCoord 1: an emissive texture on TEXCOORD_1 is seen through it, in stages 2 to 5",
          "[texture][texcoord][statistical]") {
  const EmissivePlane plane;
  std::uint32_t seed = test_seed(46800);
  for (const StageKernels& kernels : path_tracing_stages()) {
    INFO(kernels.name);
    check_scene(kernels, plane.scene, plane.image(), settings(kTexcoordSize, kTexcoordSize, 16, seed += 100), kRounding);
  }
}

TEST_CASE("texCoord 1: an alpha mask on TEXCOORD_1 cuts its holes where that set puts them, in stage1 and stage2",
          "[stage1][stage2][texture][texcoord][alpha_mask][statistical]") {
  const std::vector<uint> texels = checker(true);  // TEXCOORD_0's texel (3, 3) is opaque
  Scene scene = plane_file("mask", [&](GltfWriter& g) {
    GltfWriter::Json m = lambert(glm::vec3(1.0f));
    m["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", image_texture(g, 4, 4, texels)}, {"texCoord", 1}};
    m["alphaMode"] = "MASK";
    return m;
  });
  auto image = [&](glm::dvec3 light) {
    return expected_image(kTexcoordSize, kTexcoordSize, [&](double x0, double y0, double x1, double y1) {
      uint v = pixel_texel(texels, x0, y0, x1, y1);
      return (v >> 24) == 0u ? kSky : srgb_texel(v) * light;
    });
  };
  std::uint32_t seed = test_seed(46900);
  RenderSettings s = texcoord_sky_settings(seed);
  {
    INFO("stage1_raycast");
    Film film = render_on_test_backend(stage1::kernels(), scene, s).film;
    ExpectedImage want = image(glm::dvec3(1.0));
    int off = 0;
    for (int i = 0; i < kTexcoordSize * kTexcoordSize; i++) {
      off += glm::length(film.mean(i % kTexcoordSize, i / kTexcoordSize) - want[std::size_t(i)]) > 1e-5 * glm::length(want[std::size_t(i)]);
    }
    CHECK(off <= 1);
  }
  s.seed = seed + 100;
  check_scene(stage2::kernels(), scene, image(kSky), s, kRounding);
}

TEST_CASE("texCoord 1: a metallic-roughness texture on TEXCOORD_1 makes its half a smooth metal (Schlick) and the "
          "other half Lambert, seen at 75 degrees, in stages 2 to 5",
          "[texture][texcoord][statistical]") {
  // A plane of 4 x 10 seen by an orthographic camera turned 75 degrees about x from its
  // normal: every pixel sees it at cos 75. TEXCOORD_1: u = (x + 2) / 4 over a 2 x 1
  // texture (nearest, clamped): texel 0 (x < 0, the left half of the image) metallic 1,
  // roughness 0; texel 1 metallic 0. TEXCOORD_0 reads texel 1 everywhere.
  const double theta = 75.0 * M_PI / 180.0, c = std::cos(theta);
  const glm::dvec3 base(0.9, 0.6, 0.3);
  GltfWriter g;
  GltfWriter::Json m = lambert(glm::vec3(base));
  m["pbrMetallicRoughness"]["metallicFactor"] = 1.0;
  m["pbrMetallicRoughness"]["metallicRoughnessTexture"] = {
      {"index", image_texture(g, 2, 1, {rgba(0, 0, 255, 255), rgba(0, 0, 0, 255)})}, {"texCoord", 1}};
  const glm::vec2 same(0.75f, 0.5f);
  g.node({{"mesh", textured_quad(g, {{-2, -5, 0}, {2, -5, 0}, {2, 5, 0}, {-2, 5, 0}}, {same, same, same, same},
                                 {{0, 1}, {1, 1}, {1, 0}, {0, 0}}, g.material(m))}});
  // 10 back from the origin along the view: every ray starts above the plane.
  orthographic_camera(g, {0, -10 * std::sin(theta), 10 * c}, {std::sin(theta / 2), 0, 0, std::cos(theta / 2)});
  Scene scene = load_gltf(g.write(pt_test::scratch_dir("pt_texcoord_images").string() + "/metallic.gltf"));
  ExpectedImage want = expected_image(kTexcoordSize, kTexcoordSize, [&](double x0, double, double x1, double) {
    return kSky * (x0 + x1 < 0.0 ? gltf_schlick(base, c) : base);
  });
  std::uint32_t seed = test_seed(47000);
  for (const StageKernels& kernels : path_tracing_stages()) {
    INFO(kernels.name);
    check_scene(kernels, scene, want, texcoord_sky_settings(seed += 100), kRounding);
  }
}

TEST_CASE("KHR_materials_specular: where specularTexture's alpha is 0 the dielectric is its Lambert base (albedo "
          "x sky), where it is 1 the full layer's integrated albedo, in stages 2 to 5",
          "[texture][texcoord][specular_texture][gltf_material][statistical]") {
  // The texture on TEXCOORD_1, 2 x 1 texels (nearest, clamped): alpha 0 on the image's left
  // half, 255 on its right. TEXCOORD_0 ((0.9, 0.9)) would read texel 1 everywhere.
  GltfBrdf b;
  b.base = {0.7, 0.4, 0.2}, b.metallic = 0.0, b.roughness = 0.5;
  Scene scene = plane_file("specular_texture", [&](GltfWriter& g) {
    GltfWriter::Json m = {{"pbrMetallicRoughness",
                           {{"baseColorFactor", {b.base.x, b.base.y, b.base.z, 1.0}}, {"metallicFactor", 0.0},
                            {"roughnessFactor", b.roughness}}}};
    int tex = image_texture(g, 2, 1, {rgba(255, 255, 255, 0), rgba(255, 255, 255, 255)});
    m["extensions"] = {{"KHR_materials_specular", {{"specularTexture", {{"index", tex}, {"texCoord", 1}}}}}};
    return m;
  });
  REQUIRE(scene.materials.at(0).kind == kMaterialDielectric);
  const glm::dvec3 layered = gltf_albedo(b, 1.0);
  ExpectedImage want = expected_image(kTexcoordSize, kTexcoordSize, [&](double x0, double, double x1, double) {
    return kSky * (x0 + x1 < 0.0 ? b.base : layered);
  });
  std::uint32_t seed = test_seed(47100);
  for (const StageKernels& kernels : path_tracing_stages()) {
    INFO(kernels.name);
    // The albedo integral's own error (midpoint rule) is below 1e-3 of it.
    check_scene(kernels, scene, want, texcoord_sky_settings(seed += 100), 1e-3);
  }
}

TEST_CASE("KHR_materials_specular: specularColorTexture (sRGB) and specularTexture scale their factors as the same "
          "factors would, F0 clamped after the texture, in stages 2 to 5",
          "[texture][specular_texture][gltf_material][statistical]") {
  // One texel (255, 128, 64, 128): specularTexture reads its alpha (linear), specular-
  // ColorTexture its colour (sRGB). With specularColorFactor 30 and ior 1.5, F0 = min(0.04 x
  // 30 x colour, 1) = (1, 0.259, 0.062); clamping the factor's F0 (1.2) before the texture
  // scales it would give (1, 0.216, 0.051). The factor-only file has the products as factors.
  const uint texel = rgba(255, 128, 64, 128);
  GltfBrdf b;
  b.base = {0.3, 0.5, 0.7}, b.metallic = 0.0, b.roughness = 0.5;
  b.specular = 0.9 * 128.0 / 255.0;
  b.specular_color = 30.0 * srgb_texel(texel);
  auto material = [&](GltfWriter& g, bool textured) {
    GltfWriter::Json m = {{"pbrMetallicRoughness",
                           {{"baseColorFactor", {b.base.x, b.base.y, b.base.z, 1.0}}, {"metallicFactor", 0.0},
                            {"roughnessFactor", b.roughness}}}};
    GltfWriter::Json spec;
    if (textured) {
      int tex = image_texture(g, 1, 1, {texel});
      spec = {{"specularFactor", 0.9}, {"specularColorFactor", {30.0, 30.0, 30.0}},
              {"specularTexture", {{"index", tex}}}, {"specularColorTexture", {{"index", tex}, {"texCoord", 1}}}};
    } else {
      spec = {{"specularFactor", b.specular},
              {"specularColorFactor", {b.specular_color.x, b.specular_color.y, b.specular_color.z}}};
    }
    m["extensions"] = {{"KHR_materials_specular", spec}};
    return m;
  };
  Scene textured = plane_file("specular_color_texture", [&](GltfWriter& g) { return material(g, true); });
  Scene factors = plane_file("specular_color_factor", [&](GltfWriter& g) { return material(g, false); });
  const ExpectedImage want(kTexcoordSize * kTexcoordSize, kSky * gltf_albedo(b, 1.0));
  std::uint32_t seed = test_seed(47200);
  for (const StageKernels& kernels : path_tracing_stages()) {
    INFO(kernels.name);
    {
      INFO("textures");
      check_scene(kernels, textured, want, texcoord_sky_settings(seed += 100), 1e-3);
    }
    {
      INFO("the same factors, no textures");
      check_scene(kernels, factors, want, texcoord_sky_settings(seed += 100), 1e-3);
    }
  }
}
