// The scene's feature set (scene.h): the shapes, the lobes its materials scatter by (those a
// metallic-roughness texture reaches included), textures, alpha masks, the light kinds and
// the sky, as kFeature* bits and as the summary line's words. Not part of the article: the
// specialised kernels (docs/README.md, "Specialised kernels") carry only these features' code.
#include "common/scene/scene.h"

#include <algorithm>
#include <string>
#include <vector>

namespace pt {

uint scene_feature_mask(const Scene& scene, glm::vec3 sky) {
  uint mask = 0u;
  std::vector<char> tex_seen;  // the textured materials already counted
  if (!scene.triangles.empty()) mask |= kFeatureTriangles;
  if (!scene.spheres.empty()) mask |= kFeatureSpheres;
  auto add_material = [&](const Material& m) {
    switch (m.kind) {
      case kMaterialDiffuse: mask |= kFeatureDiffuse; break;
      case kMaterialMirror: mask |= kFeatureMirror; break;
      case kMaterialConductor:  // below kGgxMirrorAlpha the kernels scatter it as a mirror
        mask |= kFeatureConductor | (m.alpha < kGgxMirrorAlpha ? kFeatureMirror : 0u);
        break;
      case kMaterialGlass: mask |= kFeatureGlass; break;
      case kMaterialRoughGlass: mask |= kFeatureRoughGlass; break;  // its texture keeps it rough (texture.glsl)
      case kMaterialDielectric:  // the dielectric, and the conductor when metallic is above 0
        mask |= kFeatureDielectric | kFeatureDiffuse;
        if (m.metallic > 0.0f) mask |= m.alpha >= kGgxMirrorAlpha ? kFeatureConductor : kFeatureMirror;
        // Transmission between 0 and 1: its glass part (choose_gltf_lobe's glass_part).
        if (m.transmission > 0.0f)
          mask |= m.alpha >= kGgxMirrorAlpha && m.ior != 1.0f ? kFeatureRoughGlass : kFeatureGlass;
        break;
      default:  // mixed: the diffuse lobe, and the conductor's (a mirror when alpha is 0)
        mask |= kFeatureMixed | kFeatureDiffuse | (m.alpha >= kGgxMirrorAlpha ? kFeatureConductor : kFeatureMirror);
    }
  };
  // A metallic-roughness texture makes metallic and roughness vary over the surface
  // (texture.glsl: surface_material): every kind the range of its texels reaches counts.
  auto add_textured = [&](uint index) {
    const Material& m = scene.materials[index];
    uint tex = uses_textures(scene) ? scene.material_textures[index].metallic_roughness : kNoTexture;
    if (tex == kNoTexture || m.kind == kMaterialGlass || m.kind == kMaterialRoughGlass) return add_material(m);
    if (tex_seen.size() < scene.materials.size()) tex_seen.resize(scene.materials.size(), 0);
    if (tex_seen[index]) return;
    tex_seen[index] = 1;
    const MaterialTextures& mt = scene.material_textures[index];
    const Texture& t = scene.textures[tex];
    auto channel = [](uint packed, int c) { return float(packed >> (8 * c) & 255u) / 255.0f; };
    float m_lo = mt.metallic_factor * channel(t.texel_min, 2), m_hi = mt.metallic_factor * channel(t.texel_max, 2);
    float r_lo = mt.roughness_factor * channel(t.texel_min, 1), r_hi = mt.roughness_factor * channel(t.texel_max, 1);
    // Between the extremes every value is reached (bilinear filtering): one in between too.
    float m_mid = 0.5f * (std::max(m_lo, 0.0f) + std::min(m_hi, 1.0f));
    for (float metallic : {m_lo, m_mid, m_hi}) {
      for (float roughness : {r_lo, r_hi}) {
        if (m.kind == kMaterialDielectric) {  // stays a glTF material (texture.glsl)
          Material at = m;
          at.metallic = std::clamp(metallic, 0.0f, 1.0f), at.alpha = roughness * roughness;
          add_material(at);
        } else {
          add_material(make_gltf_material(m.base_color, metallic, roughness, 0.0f, m.ior, m.emission, false));
        }
      }
    }
  };
  for (const Triangle& t : scene.triangles) add_textured(t.material);
  for (const Sphere& s : scene.spheres) add_material(scene.materials[s.material]);
  if (uses_textures(scene)) mask |= kFeatureTextures;
  if (uses_alpha_mask(scene)) mask |= kFeatureAlphaMask;
  if (uses_shading_normals(scene)) mask |= kFeatureShadingNormals;
  for (const Light& l : scene.lights) {
    if (l.kind == kLightTriangle) mask |= kFeatureTriangleLights;
    if (l.kind == kLightSphere) mask |= kFeatureSphereLights;
  }
  if (!scene.point_lights.empty()) mask |= kFeaturePointLights;
  if (sky.x > 0.0f || sky.y > 0.0f || sky.z > 0.0f) mask |= kFeatureSky;
  if (scene.environment) mask |= kFeatureSky | kFeatureEnvironment;
  return mask;
}

std::string feature_names(uint mask) {
  struct Name {
    uint bit;
    const char* name;
  };
  const Name groups[3][11] = {
      {{kFeatureTriangles, "triangles"}, {kFeatureSpheres, "spheres"}},
      {{kFeatureDiffuse, "diffuse"}, {kFeatureMirror, "mirror"}, {kFeatureConductor, "GGX conductor"},
       {kFeatureGlass, "glass"}, {kFeatureMixed, "mixed"}, {kFeatureDielectric, "glTF dielectric"},
       {kFeatureRoughGlass, "rough glass"},
       {kFeatureTextures, "textures"}, {kFeatureAlphaMask, "alpha masks"},
       {kFeatureShadingNormals, "shading normals"}},
      {{kFeatureTriangleLights, "emissive triangles"}, {kFeatureSphereLights, "emissive spheres"},
       {kFeaturePointLights, "punctual lights"}, {kFeatureSky, "sky"}, {kFeatureEnvironment, "environment map"}}};
  std::string s;
  for (int g = 0; g < 3; g++) {
    std::string part;
    for (const Name& n : groups[g]) {
      if (n.name && (mask & n.bit)) part += (part.empty() ? "" : ", ") + std::string(n.name);
    }
    s += (g ? "; " : "") + (part.empty() ? std::string("none") : part);
  }
  return s;
}

std::string scene_features(const Scene& scene, glm::vec3 sky) {
  return feature_names(scene_feature_mask(scene, sky));
}

}  // namespace pt
