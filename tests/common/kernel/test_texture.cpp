// Texture lookups (common/kernel/texture.glsl), compiled as the CPU kernels compile it: the
// sRGB decoding of known texel values, the three wrap modes, the bilinear weights and the
// nearest texel at known uv, the uv transform, and the shaded material: base colour x
// texture x COLOR_0, emission x texture, metallic and roughness from a metallic-roughness
// texture by make_gltf_material's rule, and the emission light sampling sees.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "common/scene/scene.h"
#include "cpu/kernel_prelude.h"
#include "common/base/srgb.h"
#include "tests/support/texels.h"

namespace {  // internal linkage: each test file compiles its own copy of the kernel code
namespace kernel {
#include "cpu/kernel_begin.h"
#include "common/kernel/camera.glsl"
#include "common/kernel/intersect.glsl"
#include "common/kernel/texture.glsl"
#include "cpu/kernel_support.h"
#include "tests/support/kernel_scene_binding.h"
}  // namespace kernel
}  // namespace

namespace {

using pt::uint;
using pt_test::rgba;

// One texture of the given texels (row 0 on top) bound alone, with its sampler.
struct BoundTexture {
  std::vector<pt::Texture> table;
  std::vector<uint> texels;
  BoundTexture(uint width, uint height, std::vector<uint> values, uint wrap_s, uint wrap_t, uint filter)
      : table{pt::Texture{0u, width, height, wrap_s, wrap_t, filter, 0u, 0u}}, texels(std::move(values)) {
    kernel::textures = table.data();
    kernel::texels = texels.data();
  }
};

// The 2 x 2 texture of the bilinear tests, channels in [0, 1] when read linear.
const std::vector<uint> k2x2 = {rgba(0, 40, 80, 255), rgba(255, 60, 100, 255), rgba(20, 200, 0, 128),
                                rgba(100, 0, 255, 0)};

glm::dvec4 linear_texel(uint v) {
  return glm::dvec4(v & 255u, v >> 8 & 255u, v >> 16 & 255u, v >> 24) / 255.0;
}

void check_vec4(glm::vec4 got, glm::dvec4 want, double margin = 2e-6) {
  INFO("got (" << got.x << ", " << got.y << ", " << got.z << ", " << got.w << "), want (" << want.x << ", "
               << want.y << ", " << want.z << ", " << want.w << ")");
  CHECK(got.x == Approx(want.x).margin(margin));
  CHECK(got.y == Approx(want.y).margin(margin));
  CHECK(got.z == Approx(want.z).margin(margin));
  CHECK(got.w == Approx(want.w).margin(margin));
}

}  // namespace

TEST_CASE("texture: sRGB texels decode by the exact sRGB EOTF", "[texture]") {
  // 128 / 255 -> ((128 / 255 + 0.055) / 1.055)^2.4 = 0.2158605
  CHECK(kernel::srgb_to_linear(128.0f / 255.0f) == Approx(0.2158605).epsilon(1e-6));
  CHECK(kernel::srgb_to_linear(10.0f / 255.0f) == Approx(10.0 / 255.0 / 12.92).epsilon(1e-6));  // the linear segment
  CHECK(kernel::srgb_to_linear(0.0f) == 0.0f);
  CHECK(kernel::srgb_to_linear(1.0f) == 1.0f);
  // Every 8-bit value against the formula in double.
  for (int i = 0; i < 256; i++) {
    double want = pt::srgb_to_linear(i / 255.0);
    CHECK(kernel::srgb_to_linear(float(i) / 255.0f) == Approx(want).epsilon(2e-6).margin(1e-9));
  }
  // A texel read as sRGB: colour decoded, alpha linear.
  BoundTexture t(1, 1, {rgba(128, 10, 255, 128)}, pt::kWrapRepeat, pt::kWrapRepeat, pt::kFilterLinear);
  check_vec4(kernel::texture_lookup(0u, glm::vec2(0.5f, 0.5f), true),
             glm::dvec4(0.2158605, 10.0 / 255.0 / 12.92, 1.0, 128.0 / 255.0), 1e-6);
}

TEST_CASE("texture: the wrap modes map texel indices and coordinates into the image", "[texture]") {
  using namespace pt;
  // REPEAT: period n. CLAMP_TO_EDGE: the edge texels. MIRRORED_REPEAT: 0 1 2 3 3 2 1 0 0 1 ...
  CHECK(kernel::wrap_texel(-1, 4, kWrapRepeat) == 3u);
  CHECK(kernel::wrap_texel(4, 4, kWrapRepeat) == 0u);
  CHECK(kernel::wrap_texel(2, 4, kWrapRepeat) == 2u);
  CHECK(kernel::wrap_texel(-1, 4, kWrapClampToEdge) == 0u);
  CHECK(kernel::wrap_texel(9, 4, kWrapClampToEdge) == 3u);
  const uint mirrored[] = {0, 1, 2, 3, 3, 2, 1, 0, 0};
  for (int i = 0; i <= 8; i++) CHECK(kernel::wrap_texel(i, 4, kWrapMirroredRepeat) == mirrored[i]);
  CHECK(kernel::wrap_texel(-1, 4, kWrapMirroredRepeat) == 0u);
  CHECK(kernel::wrap_coordinate(1.25f, kWrapRepeat) == 0.25f);
  CHECK(kernel::wrap_coordinate(-0.25f, kWrapRepeat) == 0.75f);
  CHECK(kernel::wrap_coordinate(3.25f, kWrapMirroredRepeat) == 1.25f);
  CHECK(kernel::wrap_coordinate(-0.25f, kWrapMirroredRepeat) == 1.75f);
  CHECK(kernel::wrap_coordinate(5.0f, kWrapClampToEdge) == 2.0f);
  CHECK(kernel::wrap_coordinate(std::nanf(""), kWrapRepeat) == 0.0f);
  CHECK(kernel::wrap_coordinate(1e30f, kWrapMirroredRepeat) == 0.0f);
}

TEST_CASE("texture: bilinear weights and the nearest texel at known uv, under each wrap mode", "[texture]") {
  using namespace pt;
  const glm::dvec4 t00 = linear_texel(k2x2[0]), t10 = linear_texel(k2x2[1]), t01 = linear_texel(k2x2[2]),
                   t11 = linear_texel(k2x2[3]);
  {
    BoundTexture t(2, 2, k2x2, kWrapRepeat, kWrapRepeat, kFilterLinear);
    check_vec4(kernel::texture_lookup(0u, glm::vec2(0.25f, 0.25f), false), t00);  // a texel's centre: that texel
    check_vec4(kernel::texture_lookup(0u, glm::vec2(0.75f, 0.75f), false), t11);
    check_vec4(kernel::texture_lookup(0u, glm::vec2(0.5f, 0.5f), false), 0.25 * (t00 + t10 + t01 + t11));
    // x = 0.375 * 2 - 0.5 = 0.25 texels past t00's centre: weights 0.75, 0.25.
    check_vec4(kernel::texture_lookup(0u, glm::vec2(0.375f, 0.25f), false), 0.75 * t00 + 0.25 * t10);
    // (0.375, 0.625): 0.25 past t00 in x, 0.75 past in y.
    check_vec4(kernel::texture_lookup(0u, glm::vec2(0.375f, 0.625f), false),
               0.25 * (0.75 * t00 + 0.25 * t10) + 0.75 * (0.75 * t01 + 0.25 * t11));
    // REPEAT at the corner: the four texels of the wrapped neighbourhood, equally.
    check_vec4(kernel::texture_lookup(0u, glm::vec2(0.0f, 0.0f), false), 0.25 * (t00 + t10 + t01 + t11));
    check_vec4(kernel::texture_lookup(0u, glm::vec2(1.0f, 0.25f), false), 0.5 * (t00 + t10));
    check_vec4(kernel::texture_lookup(0u, glm::vec2(-0.75f, 2.25f), false), t00);  // whole periods away
  }
  {
    BoundTexture t(2, 2, k2x2, kWrapClampToEdge, kWrapClampToEdge, kFilterLinear);
    check_vec4(kernel::texture_lookup(0u, glm::vec2(0.0f, 0.0f), false), t00);
    check_vec4(kernel::texture_lookup(0u, glm::vec2(-3.0f, 0.25f), false), t00);
    check_vec4(kernel::texture_lookup(0u, glm::vec2(1.0f, 7.0f), false), t11);
  }
  {
    BoundTexture t(2, 2, k2x2, kWrapMirroredRepeat, kWrapMirroredRepeat, kFilterLinear);
    check_vec4(kernel::texture_lookup(0u, glm::vec2(0.0f, 0.0f), false), t00);
    check_vec4(kernel::texture_lookup(0u, glm::vec2(1.0f, 0.25f), false), t10);
    check_vec4(kernel::texture_lookup(0u, glm::vec2(1.25f, 0.25f), false), t10);  // the mirrored copy of (0.75, 0.25)
    check_vec4(kernel::texture_lookup(0u, glm::vec2(1.75f, 0.25f), false), t00);
  }
  {
    BoundTexture t(2, 2, k2x2, kWrapRepeat, kWrapRepeat, kFilterNearest);
    check_vec4(kernel::texture_lookup(0u, glm::vec2(0.49f, 0.51f), false), t01);
    check_vec4(kernel::texture_lookup(0u, glm::vec2(0.51f, 0.49f), false), t10);
    check_vec4(kernel::texture_lookup(0u, glm::vec2(-0.01f, 0.99f), false), t11);
    check_vec4(kernel::texture_lookup(0u, glm::vec2(1.0f, 1.0f), false), t00);
  }
  {
    BoundTexture t(4, 1, {rgba(0, 0, 0, 0), rgba(255, 0, 0, 0), rgba(0, 255, 0, 0), rgba(0, 0, 255, 0)}, kWrapClampToEdge,
                   kWrapRepeat, kFilterNearest);
    for (int i = 0; i < 4; i++) {
      glm::vec4 got = kernel::texture_lookup(0u, glm::vec2((float(i) + 0.5f) / 4.0f, 0.5f), false);
      CHECK(got == glm::vec4(i == 1 ? 1.0f : 0.0f, i == 2 ? 1.0f : 0.0f, i == 3 ? 1.0f : 0.0f, 0.0f));
    }
  }
}

TEST_CASE("texture: a constant texture gives its constant exactly, at any uv", "[texture]") {
  using namespace pt;
  for (uint filter : {kFilterLinear, kFilterNearest}) {
    BoundTexture t(3, 2, std::vector<uint>(6, rgba(255, 255, 255, 255)), kWrapMirroredRepeat, kWrapRepeat, filter);
    for (float u : {-7.3f, 0.0f, 0.1234f, 0.5f, 0.999f, 12.7f}) {
      CHECK(kernel::texture_lookup(0u, glm::vec2(u, 1.0f - u), true) == glm::vec4(1.0f));
    }
  }
}

TEST_CASE("texture: the shaded material of a textured triangle", "[texture]") {
  using namespace pt;
  Scene s;
  // Base colour factor (0.5, 0.8, 1), emission 2, metallic and roughness factors 1 and 0.5.
  Material m = make_gltf_material({0.5f, 0.8f, 1.0f}, 1.0f, 0.5f, 0.0f, 1.5f, glm::vec3(2.0f), false);
  s.add_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, s.add_material(m));
  s.material_textures.assign(1, no_material_textures());
  s.triangle_attributes.assign(1, no_triangle_attributes());
  MaterialTextures& mt = s.material_textures[0];
  mt.metallic_factor = 1.0f, mt.roughness_factor = 0.5f;
  TriangleAttributes& a = s.triangle_attributes[0];
  a.uv0 = {0.25f, 0.25f}, a.uv1 = {0.75f, 0.25f}, a.uv2 = {0.25f, 0.75f};
  a.color0 = {1.0f, 0.5f, 0.25f, 1.0f}, a.color1 = {0.5f, 1.0f, 0.5f, 1.0f}, a.color2 = {0.0f, 0.5f, 1.0f, 1.0f};
  // One 2 x 2 texture, nearest, read by all three slots.
  s.textures.push_back(Texture{0u, 2u, 2u, kWrapRepeat, kWrapRepeat, kFilterNearest, 0u, 0u});
  s.texels = {rgba(128, 255, 0, 255), rgba(255, 0, 255, 255), rgba(255, 64, 128, 255), rgba(10, 20, 30, 255)};
  mt.base_color = mt.emissive = mt.metallic_roughness = 0u;
  kernel::bind_scene(s);
  kernel::triangle_attributes = s.triangle_attributes.data();
  kernel::material_textures = s.material_textures.data();
  kernel::textures = s.textures.data();
  kernel::texels = s.texels.data();
  // At corner 0 (uv (0.25, 0.25): texel (0, 0)); at the centroid (uv 5/12, 5/12: texel (0, 0)).
  for (float b : {0.0f, 1.0f / 3.0f}) {
    Material got = kernel::textured_material(0u, 0u, b, b);
    glm::dvec3 color = glm::dvec3(a.color0) * (1.0 - 2.0 * b) + glm::dvec3(a.color1) * double(b) +
                       glm::dvec3(a.color2) * double(b);
    glm::dvec3 tex(pt::srgb_to_linear(128 / 255.0), 1.0, 0.0);
    glm::dvec3 base = glm::dvec3(m.base_color) * tex * color;
    INFO("barycentric " << b);
    CHECK(got.base_color.x == Approx(base.x).epsilon(1e-5));
    CHECK(got.base_color.y == Approx(base.y).epsilon(1e-5));
    CHECK(got.base_color.z == Approx(base.z).margin(1e-7));
    CHECK(got.emission.x == Approx(2.0 * tex.x).epsilon(1e-5));
    CHECK(got.emission.y == 2.0f);
    CHECK(got.emission.z == 0.0f);
    // metallic = 1 x B (0): diffuse, as make_gltf_material(metallic 0) is.
    CHECK(got.kind == kMaterialDiffuse);
    CHECK(got.metallic == 0.0f);
    // Light sampling sees the same emission at the same point.
    glm::vec3 e = kernel::triangle_emission(0u, b, b);
    CHECK(e == got.emission);
    glm::vec3 at = kernel::triangle_emission_at(0u, glm::vec3(b, b, 0.0f));
    CHECK(at.x == Approx(e.x).epsilon(1e-6));
  }
  // Texel (1, 0): B 255, G 0: metallic 1, roughness 0: a mirror.
  a.uv0 = a.uv1 = a.uv2 = {0.75f, 0.25f};
  Material mirror = kernel::textured_material(0u, 0u, 0.2f, 0.3f);
  CHECK(mirror.kind == kMaterialMirror);
  // Texel (0, 1): B 128, G 64: mixed, metallic 128 / 255, alpha (0.5 x 64 / 255)^2.
  a.uv0 = a.uv1 = a.uv2 = {0.25f, 0.75f};
  Material mixed = kernel::textured_material(0u, 0u, 0.2f, 0.3f);
  CHECK(mixed.kind == kMaterialMixed);
  CHECK(mixed.metallic == Approx(128.0 / 255.0).epsilon(1e-6));
  CHECK(mixed.alpha == Approx(std::pow(0.5 * 64.0 / 255.0, 2.0)).epsilon(1e-5));
  // A sphere's surface, or a kernel without textures: the material as it is.
  kernel::Surface sphere(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1.0f), true, 0u, kernel::kNoTriangle, 0.0f, 0.0f, false);
  CHECK(kernel::surface_material(sphere).base_color == m.base_color);
}

TEST_CASE("texture: metallic and roughness from a texture give make_gltf_material's material", "[texture]") {
  using namespace pt;
  const Material start = make_gltf_material({0.6f, 0.5f, 0.4f}, 0.5f, 0.5f, 0.0f, 1.5f, glm::vec3(0.0f), false);
  for (float metallic : {0.0f, 1e-6f, 0.3f, 0.999f, 1.0f}) {
    for (float roughness : {0.0f, 1e-4f, 0.5f, 1.0f}) {
      Material want = make_gltf_material(start.base_color, metallic, roughness, 0.0f, 1.5f, glm::vec3(0.0f), false);
      Material got = kernel::with_metallic_roughness(start, metallic, roughness);
      INFO("metallic " << metallic << ", roughness " << roughness);
      CHECK(got.kind == want.kind);
      CHECK(got.metallic == want.metallic);
      CHECK(got.alpha == want.alpha);
      CHECK(got.base_color == want.base_color);
    }
  }
}
