// Scene helpers: the Scene's own methods (bounds, appending), the material rules of the
// contract (README.md), the punctual lights' constructors, and the defaults of textures and
// vertex attributes. The light table: scene_lights.cpp; the feature set: scene_features.cpp;
// the camera: scene_camera.cpp; the built-in scenes' shapes: scene_shapes.cpp.
#include "common/scene/scene.h"

#include <algorithm>
#include <cmath>

namespace pt {

Bounds Scene::bounds() const {
  if (region) return *region;
  Bounds b;
  for (const Triangle& t : triangles) {
    b.extend(t.p0), b.extend(t.p1), b.extend(t.p2);
  }
  for (const Sphere& s : spheres) {
    b.extend(s.center - s.radius), b.extend(s.center + s.radius);
  }
  return b;
}

uint Scene::add_material(const Material& m) {
  materials.push_back(m);
  if (!material_textures.empty()) material_textures.push_back(no_material_textures());
  return uint(materials.size() - 1);
}

void Scene::add_triangle(glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, uint material) {
  triangles.push_back(Triangle{p0, material, p1, kNoLight, p2, 0u});
  if (!triangle_attributes.empty()) triangle_attributes.push_back(no_triangle_attributes());
  if (!triangle_shading.empty()) triangle_shading.push_back(flat_shading(triangles.back()));
}

void Scene::add_sphere(glm::vec3 center, float radius, uint material) {
  spheres.push_back(Sphere{center, radius, material, kNoLight, 0u, 0u});
}

namespace {
Material base_material(glm::vec3 color, uint kind) {
  Material m{};
  m.base_color = color;
  m.metallic = 0.0f, m.alpha = 1.0f, m.transmission = 0.0f, m.ior = 1.5f;
  m.kind = kind;
  return m;
}
}  // namespace

Material make_diffuse(glm::vec3 albedo, glm::vec3 emission, bool double_sided) {
  Material m = base_material(albedo, kMaterialDiffuse);
  m.emission = emission;
  m.double_sided = double_sided ? 1u : 0u;
  return m;
}

PointLight make_point_light(glm::vec3 position, glm::vec3 intensity) {
  return PointLight{position, kPunctualPoint, intensity, 0.0f, glm::vec3(0.0f), 0.0f};
}

PointLight make_spot_light(glm::vec3 position, glm::vec3 direction, glm::vec3 intensity, float inner, float outer) {
  return PointLight{position, kPunctualSpot, intensity, std::cos(outer), glm::normalize(direction), std::cos(inner)};
}

PointLight make_directional_light(glm::vec3 direction, glm::vec3 irradiance) {
  return PointLight{glm::vec3(0.0f), kPunctualDirectional, irradiance, 0.0f, glm::normalize(direction), 0.0f};
}

Material make_metal(glm::vec3 f0, float roughness) {
  Material m = base_material(f0, roughness > 0.0f ? kMaterialConductor : kMaterialMirror);
  m.metallic = 1.0f, m.alpha = roughness * roughness, m.transmission = 0.0f, m.ior = 1.5f;
  return m;
}

Material make_glass(glm::vec3 tint, float ior) {
  Material m = base_material(tint, kMaterialGlass);
  m.metallic = 0.0f, m.alpha = 0.0f, m.transmission = 1.0f, m.ior = ior;
  return m;
}

Material make_rough_glass(glm::vec3 tint, float ior, float roughness) {
  Material m = make_glass(tint, ior);
  m.kind = kMaterialRoughGlass;
  m.alpha = std::max(roughness * roughness, kGgxMirrorAlpha);
  return m;
}

Material make_gltf_material(glm::vec3 base, float metallic, float roughness, float transmission,
                            float ior, glm::vec3 emission, bool double_sided) {
  Material m;
  if (transmission > 0.0f) {
    // Rough glass at roughness > 0; smooth glass at 0, and at ior 1, where no microfacet
    // bends the light and the rough refraction's half vector is undefined.
    m = roughness > 0.0f && ior != 1.0f ? make_rough_glass(base, ior, roughness) : make_glass(base, ior);
  } else if (metallic >= 1.0f) {
    m = make_metal(base, roughness);
  } else if (metallic <= 0.0f) {
    m = make_diffuse(base);
  } else {
    m = base_material(base, kMaterialMixed);
    m.metallic = metallic, m.alpha = roughness * roughness, m.transmission = 0.0f, m.ior = ior;
  }
  m.transmission = transmission;
  m.emission = emission;
  m.double_sided = double_sided ? 1u : 0u;
  return m;
}

Material make_gltf_pbr_material(const GltfPbr& p) {
  bool pure_metal = p.metallic >= 1.0f && !p.textured_metallic_roughness;
  // Transmission between 0 and 1 (docs/gltf_material.md, "Partial transmission"): the glTF
  // dielectric with its transmission, whose glass part choose_gltf_lobe picks with
  // probability (1 - metallic) T; a metal ignores it (metallic 1: the conductor alone).
  // A transmissionTexture makes a factor of 1 partial too (its texels below 1), except on a
  // pure metal, where transmission 1 wins as without the texture.
  bool partial = p.transmission > 0.0f && (p.transmission < 1.0f || (p.textured_transmission && !pure_metal));
  if (partial && pure_metal) {
    return make_gltf_material(p.base, p.metallic, p.roughness, 0.0f, p.ior, p.emission, p.double_sided);
  }
  if ((p.transmission > 0.0f && !partial) || pure_metal || (p.specular <= 0.0f && !partial)) {
    return make_gltf_material(p.base, p.metallic, p.roughness, p.transmission, p.ior, p.emission, p.double_sided);
  }
  Material m = base_material(p.base, kMaterialDielectric);
  m.transmission = p.transmission;
  m.metallic = p.metallic, m.alpha = p.roughness * p.roughness, m.ior = p.ior;
  float r = (p.ior - 1.0f) / (p.ior + 1.0f);
  m.specular_f0 = glm::min(r * r * p.specular_color, glm::vec3(1.0f));
  m.specular = p.specular;
  m.emission = p.emission;
  m.double_sided = p.double_sided ? 1u : 0u;
  return m;
}

bool is_emissive(const Material& m) {
  return m.emission.x > 0.0f || m.emission.y > 0.0f || m.emission.z > 0.0f;
}

bool uses_textures(const Scene& scene) {
  return !scene.material_textures.empty() && !scene.triangle_attributes.empty();
}

void mark_alpha_masked(Scene& scene) {
  const bool textured = uses_textures(scene);
  for (Triangle& t : scene.triangles) {
    bool masked = textured && scene.material_textures[t.material].alpha_cutoff > 0.0f;
    t.flags = masked ? t.flags | kTriangleMasked : t.flags & ~kTriangleMasked;
  }
}

bool uses_alpha_mask(const Scene& scene) {
  if (!uses_textures(scene)) return false;
  for (const Triangle& t : scene.triangles) {
    if (t.flags & kTriangleMasked) return true;
  }
  return false;
}

TriangleShading flat_shading(const Triangle& t) {
  const glm::vec3 n = glm::normalize(glm::cross(t.p1 - t.p0, t.p2 - t.p0));
  // Any unit vector orthogonal to n (Duff et al.'s branchless basis, as make_frame).
  const float sign = std::copysign(1.0f, n.z), a = -1.0f / (sign + n.z);
  const glm::vec3 tangent(1.0f + sign * n.x * n.x * a, sign * n.x * n.y * a, -sign * n.x);
  return TriangleShading{n, 0.0f, n, 0.0f, n, 0.0f, tangent, 1.0f, tangent, 1.0f, tangent, 1.0f};
}

bool uses_shading_normals(const Scene& scene) {
  if (scene.triangle_shading.size() != scene.triangles.size()) return false;
  for (const Triangle& t : scene.triangles) {
    if (t.flags & kTriangleShadingNormals) return true;
  }
  return false;
}

MaterialTextures no_material_textures() {
  const glm::vec3 s(1.0f, 0.0f, 0.0f), t(0.0f, 1.0f, 0.0f);  // the identity transform
  MaterialTextures m{};  // every other field 0: no transform offsets, opaque, TEXCOORD_0
  m.base_color_s = m.emissive_s = m.metallic_roughness_s = m.specular_s = m.specular_color_s = m.normal_s = s;
  m.transmission_s = s;
  m.base_color_t = m.emissive_t = m.metallic_roughness_t = m.specular_t = m.specular_color_t = m.normal_t = t;
  m.transmission_t = t;
  m.base_color = m.emissive = m.metallic_roughness = m.specular = m.specular_color = m.normal = kNoTexture;
  m.transmission = kNoTexture;
  m.metallic_factor = m.roughness_factor = m.base_alpha = m.normal_scale = 1.0f;
  m.specular_color_factor = glm::vec3(1.0f);
  m.enabled = 1u;
  return m;
}

std::vector<MaterialTextures> neutral_material_textures(std::size_t materials) {
  MaterialTextures none = no_material_textures();
  none.enabled = 0u;
  return std::vector<MaterialTextures>(std::max<std::size_t>(materials, 1), none);
}

TriangleAttributes no_triangle_attributes() {
  const glm::vec2 uv(0.0f);
  const glm::vec4 white(1.0f);
  return TriangleAttributes{uv, uv, uv, uv, white, white, white, uv, uv};
}

glm::vec4 texel_value(const Scene& scene, const Texture& t, uint x, uint y) {
  uint v = scene.texels[t.offset + std::size_t(y) * t.width + x];
  return glm::vec4(float(v & 255u), float(v >> 8 & 255u), float(v >> 16 & 255u), float(v >> 24)) / 255.0f;
}

}  // namespace pt
