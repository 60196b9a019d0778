// Scenes of the shading-normal tests (issue #46; common/kernel/shading_normal.glsl), built in
// code and run by both test executables: a Lambert plane with a strong bumpy normal map,
// tilted toward the camera; the inside of a normal-mapped emissive sphere (a furnace with a
// closed form); a coarse sphere with smooth vertex normals under a sun.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "common/scene/gltf_scene_builder.h"
#include "common/scene/scene.h"

namespace pt::test {

// An n x n normal map of tangent-space normals tilted up to ~66 degrees in random directions
// (a fixed generator), bilinear, repeated: texels encode (n + 1) / 2 in 8 bits.
inline void add_bumpy_normal_map(Scene& scene, uint n = 8) {
  Texture t{uint(scene.texels.size()), n, n, kWrapRepeat, kWrapRepeat, kFilterLinear, 0u, 0u};
  std::uint32_t state = 12345u;
  auto next = [&state]() {
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) / 16777216.0f;
  };
  uint lo = 0xffffffffu, hi = 0u;
  for (uint i = 0; i < n * n; i++) {
    float phi = 6.2831853f * next(), tilt = 1.15f * next();
    glm::vec3 v(std::sin(tilt) * std::cos(phi), std::sin(tilt) * std::sin(phi), std::cos(tilt));
    uint r = uint(std::lround((v.x + 1.0f) * 127.5f)), g = uint(std::lround((v.y + 1.0f) * 127.5f));
    uint b = uint(std::lround((v.z + 1.0f) * 127.5f));
    uint texel = r | g << 8 | b << 16 | 255u << 24;
    scene.texels.push_back(texel);
    lo = std::min(lo, texel), hi = std::max(hi, texel);  // unused but kept meaningful
  }
  t.texel_min = lo, t.texel_max = hi;
  scene.textures.push_back(t);
}

// Gives every triangle of `scene` the material's normal map (texture 0, `scale`) with uv from
// `uv_of` at its corners, tangents made from those UVs, and the shading flag.
template <class UvOf>
void normal_map_everything(Scene& scene, float scale, UvOf uv_of) {
  add_bumpy_normal_map(scene);
  scene.material_textures.assign(scene.materials.size(), no_material_textures());
  for (MaterialTextures& mt : scene.material_textures) mt.normal = 0u, mt.normal_scale = scale;
  scene.triangle_attributes.assign(scene.triangles.size(), no_triangle_attributes());
  scene.triangle_shading.clear();
  for (std::size_t i = 0; i < scene.triangles.size(); i++) {
    Triangle& t = scene.triangles[i];
    glm::vec3 p[3] = {t.p0, t.p1, t.p2};
    glm::vec2 uv[3] = {uv_of(t.p0), uv_of(t.p1), uv_of(t.p2)};
    TriangleAttributes& a = scene.triangle_attributes[i];
    a.uv0 = uv[0], a.uv1 = uv[1], a.uv2 = uv[2];
    scene.triangle_shading.push_back(gltf::tangents_from_uvs(p, uv, glm::normalize(glm::cross(p[1] - p[0], p[2] - p[0]))));
    t.flags |= kTriangleShadingNormals;
  }
}

// A white Lambert plane tilted 60 degrees about x toward the camera (an orthographic view
// down -z of half-extent 1), larger than the view, with a bumpy normal map of `scale`
// repeated 3 times over it; `mapped` false: the same plane without any shading normal.
inline Scene bumpy_plane(float scale, bool mapped = true, glm::vec3 albedo = glm::vec3(1.0f)) {
  Scene scene;
  scene.name = "bumpy plane";
  uint m = scene.add_material(make_diffuse(albedo));
  const float c = 0.5f, s = std::sqrt(0.75f);  // cos and sin of 60 degrees
  auto at = [&](float x, float y) { return glm::vec3(x, c * y, -s * y); };
  add_quad(scene, at(-1.5f, -2.5f), at(1.5f, -2.5f), at(1.5f, 2.5f), at(-1.5f, 2.5f), m);
  scene.camera = orthographic_front(3.0f, 1.0f);
  if (mapped) {
    normal_map_everything(scene, scale, [&](glm::vec3 p) { return glm::vec2(p.x + 1.5f, 1.5f - p.y / c) * 0.6f; });
  }
  build_light_table(scene);
  return scene;
}

// The inside of a sphere (an icosphere of 320 faces turned inwards) of Lambert albedo `a` and
// emission Le, normal-mapped all over, seen from its centre: every direction there carries
// Le / (1 - a), since the folded BSDF's albedo is a for every view direction.
inline Scene bumpy_furnace(float a, float Le) {
  Scene scene;
  scene.name = "bumpy furnace";
  uint m = scene.add_material(make_diffuse(glm::vec3(a), glm::vec3(Le)));
  add_icosphere(scene, glm::vec3(0.0f), 1.0f, 4, m, true);
  scene.camera = CameraDesc{};  // perspective at the centre, looking down -z
  normal_map_everything(scene, 1.0f, [](glm::vec3 p) { return glm::vec2(2.0f * p.x + p.z, 2.0f * p.y - p.z); });
  build_light_table(scene);
  return scene;
}

// A coarse sphere (an icosahedron, 20 faces) of albedo 0.8 seen from +z (orthographic,
// half-extent 1.2) under a sun shining along -z; `smooth`: vertex normals of the sphere.
inline Scene coarse_sphere(bool smooth) {
  Scene scene;
  scene.name = "coarse sphere";
  uint m = scene.add_material(make_diffuse(glm::vec3(0.8f)));
  add_icosphere(scene, glm::vec3(0.0f), 1.0f, 1, m);
  scene.point_lights.push_back(make_directional_light(glm::vec3(0.0f, 0.0f, -1.0f), glm::vec3(3.0f)));
  scene.camera = orthographic_front(3.0f, 1.2f);
  if (smooth) {
    for (Triangle& t : scene.triangles) {
      TriangleShading s = flat_shading(t);
      s.normal0 = glm::normalize(t.p0), s.normal1 = glm::normalize(t.p1), s.normal2 = glm::normalize(t.p2);
      scene.triangle_shading.push_back(s);
      t.flags |= kTriangleShadingNormals;
    }
  }
  build_light_table(scene);
  return scene;
}

}  // namespace pt::test
