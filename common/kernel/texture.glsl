// Textures and vertex colours (issue #19; the contract (README.md), "Materials"): glTF's
// base colour, emissive and metallic-roughness textures, KHR_materials_specular's two and
// KHR_materials_transmission's, each read through its TEXCOORD_0 or TEXCOORD_1 and
// KHR_texture_transform with the sampler's wrap modes and bilinear (or nearest) filtering,
// and COLOR_0, which multiplies the base colour. Beyond the article, whose materials are
// constant. Texels are 8-bit RGBA (texels[], the texture table textures[]), decoded at
// lookup: sRGB to linear for base colour, emissive and specular colour, linear for
// metallic-roughness, specular and transmission.
// Every function here runs only in kernels whose scene has kFeatureTextures (has_feature):
// without it surface_material() is materials[surface.material], as before.
#ifndef PT_TEXTURE_GLSL
#define PT_TEXTURE_GLSL

#include "common/kernel/intersect.glsl"
#include "common/kernel/texture_lookup.glsl"

// The material with metallic and roughness taken from a metallic-roughness texture:
// make_gltf_material's rule (common/scene/scene.cpp) at this point: metallic 1 is a
// conductor (a mirror at roughness 0, else GGX with alpha = roughness^2), metallic 0 is
// diffuse, between the two it is mixed. Glass stays glass (transmission wins); rough glass
// takes the roughness (below: at least kGgxMirrorAlpha). A glTF
// material (kMaterialDielectric) stays one: its metallic mixes its two parts, and its
// roughness makes its glass part (transmission between 0 and 1) smooth or rough.
Material with_metallic_roughness(Material m, float metallic, float roughness) {
  if (has_feature(kFeatureRoughGlass) && m.kind == kMaterialRoughGlass) {
    // Rough glass stays rough glass and reads only the roughness: where it is 0, alpha
    // stops at kGgxMirrorAlpha, a lobe narrower than a float direction (smooth in effect).
    m.alpha = max(roughness * roughness, kGgxMirrorAlpha);
  } else if (has_feature(kFeatureDielectric) && m.kind == kMaterialDielectric) {
    m.metallic = clamp(metallic, 0.0f, 1.0f);
    m.alpha = roughness * roughness;
  } else if (metallic >= 1.0f) {
    m.kind = roughness > 0.0f ? kMaterialConductor : kMaterialMirror;
    m.metallic = 1.0f;
    m.alpha = roughness * roughness;
  } else if (metallic <= 0.0f) {
    m.kind = kMaterialDiffuse;
    m.metallic = 0.0f;
    m.alpha = 1.0f;
  } else {
    m.kind = kMaterialMixed;
    m.metallic = metallic;
    m.alpha = roughness * roughness;
  }
  return m;
}

// KHR_materials_specular's textures at a point of a glTF dielectric: specularTexture's A
// (linear) scales the layer's weight (specularFactor), specularColorTexture's RGB (sRGB)
// its colour (specularColorFactor), and F0 is made again as the loader makes it from the
// ior and the colour (scene.cpp make_gltf_pbr_material): min(((ior - 1) / (ior + 1))^2 x
// colour, 1) per channel.
Material with_specular_textures(Material m, MaterialTextures mt, TriangleAttributes a, float b1, float b2) {
  if (mt.specular != kNoTexture) {
    vec2 uv = slot_uv(mt.tex_coord_sets, kSlotSpecular, vec3(mt.specular_s), vec3(mt.specular_t), a, b1, b2);
    m.specular = m.specular * texture_lookup(mt.specular, uv, false).w;
  }
  if (mt.specular_color != kNoTexture) {
    vec2 uv = slot_uv(mt.tex_coord_sets, kSlotSpecularColor, vec3(mt.specular_color_s), vec3(mt.specular_color_t),
                      a, b1, b2);
    vec4 c = texture_lookup(mt.specular_color, uv, true);
    float r = (m.ior - 1.0f) / (m.ior + 1.0f);
    m.specular_f0 = min(r * r * vec3(mt.specular_color_factor) * vec3(c.x, c.y, c.z), vec3(1.0f));
  }
  return m;
}

// KHR_materials_transmission's transmissionTexture at a point of a glTF dielectric: its R
// (linear) scales the transmission (transmissionFactor), which picks the glass part
// (gltf_dielectric.glsl choose_gltf_lobe).
Material with_transmission_texture(Material m, MaterialTextures mt, TriangleAttributes a, float b1, float b2) {
  if (mt.transmission == kNoTexture) return m;
  vec2 uv = slot_uv(mt.tex_coord_sets, kSlotTransmission, vec3(mt.transmission_s), vec3(mt.transmission_t), a, b1, b2);
  m.transmission = m.transmission * texture_lookup(mt.transmission, uv, false).x;
  return m;
}

// Material `material` at the point (b1, b2) of triangle `tri`: base colour x base colour
// texture x COLOR_0, emission x emissive texture, metallic = factor x B and roughness =
// factor x G of the metallic-roughness texture, and a glTF dielectric's specular and
// transmission textures;
// each texture read through its slot's texture coordinate set (slot_uv).
Material textured_material(uint material, uint tri, float b1, float b2) {
  Material m = materials[material];
  MaterialTextures mt = material_textures[material];
  if (mt.enabled == 0u) return m;  // a kernel with texture code, a scene without textures
  TriangleAttributes a = triangle_attributes[tri];
  vec4 color = triangle_color(a, b1, b2);
  vec3 base = vec3(m.base_color);
  if (mt.base_color != kNoTexture) {
    vec2 uv = slot_uv(mt.tex_coord_sets, kSlotBaseColor, vec3(mt.base_color_s), vec3(mt.base_color_t), a, b1, b2);
    vec4 t = texture_lookup(mt.base_color, uv, true);
    base = base * vec3(t.x, t.y, t.z);
  }
  m.base_color = base * vec3(color.x, color.y, color.z);
  if (mt.emissive != kNoTexture) {
    vec2 uv = slot_uv(mt.tex_coord_sets, kSlotEmissive, vec3(mt.emissive_s), vec3(mt.emissive_t), a, b1, b2);
    vec4 e = texture_lookup(mt.emissive, uv, true);
    m.emission = vec3(m.emission) * vec3(e.x, e.y, e.z);
  }
  if (mt.metallic_roughness != kNoTexture && m.kind != kMaterialGlass) {
    vec2 uv = slot_uv(mt.tex_coord_sets, kSlotMetallicRoughness, vec3(mt.metallic_roughness_s),
                      vec3(mt.metallic_roughness_t), a, b1, b2);
    vec4 r = texture_lookup(mt.metallic_roughness, uv, false);
    m = with_metallic_roughness(m, mt.metallic_factor * r.z, mt.roughness_factor * r.y);
  }
  if (has_feature(kFeatureDielectric) && m.kind == kMaterialDielectric) {
    m = with_specular_textures(m, mt, a, b1, b2);
    m = with_transmission_texture(m, mt, a, b1, b2);
  }
  return m;
}

// The material the integrators shade a surface point with: materials[surface.material],
// with its textures and the vertex colour applied where the scene has them. (A kernel
// with texture code may render a scene without: its backend binds neutral entries of
// material_textures[], which name no texture and are not enabled.)
// Rough glass's ior is made relative to the side the ray arrives from: inverted on a back
// face; so is a glTF dielectric's whose transmission has a rough glass part (glass_part;
// its dielectric part reads F0, made from the ior before this).
Material surface_material(Surface surface) {
  if (has_feature(kFeatureRoughGlass)) {
    Material m = materials[surface.material];
    if (has_feature(kFeatureTextures) && surface.triangle != kNoTriangle) {
      m = textured_material(surface.material, surface.triangle, surface.b1, surface.b2);
    }
    bool rough_part = m.kind == kMaterialDielectric && m.transmission > 0.0f && m.alpha >= kGgxMirrorAlpha;
    if ((m.kind == kMaterialRoughGlass || rough_part) && !surface.front) m.ior = 1.0f / m.ior;
    return m;
  }
  if (!has_feature(kFeatureTextures) || surface.triangle == kNoTriangle) return materials[surface.material];
  return textured_material(surface.material, surface.triangle, surface.b1, surface.b2);
}

// The emitted radiance factor (before the front-face rule) of triangle `tri` at the point
// of barycentric weights b1 (p1), b2 (p2): its material's emission times its emissive
// texture there, what surface_material() gives at the same point. Light sampling
// (lights.glsl, triangle_light.glsl) weighs a point sampled on a triangle light with it.
vec3 triangle_emission(uint tri, float b1, float b2) {
  uint material = triangle_at(tri).material;
  if (!has_feature(kFeatureTextures)) return vec3(materials[material].emission);
  uint tex = material_textures[material].emissive;
  if (tex == kNoTexture) return vec3(materials[material].emission);
  MaterialTextures mt = material_textures[material];
  vec2 uv = slot_uv(mt.tex_coord_sets, kSlotEmissive, vec3(mt.emissive_s), vec3(mt.emissive_t),
                    triangle_attributes[tri], b1, b2);
  vec4 e = texture_lookup(tex, uv, true);
  return vec3(materials[material].emission) * vec3(e.x, e.y, e.z);
}

// The barycentric weights (b1 of p1, b2 of p2) of the point y on the plane of triangle
// `tri`, from the areas of the sub-triangles.
vec2 barycentric_at(uint tri, vec3 y) {
  Triangle t = triangle_at(tri);
  vec3 p0 = t.p0;
  vec3 e1 = vec3(t.p1) - p0;
  vec3 e2 = vec3(t.p2) - p0;
  vec3 n = cross(e1, e2);
  vec3 d = y - p0;
  float inv = 1.0f / dot(n, n);
  return vec2(dot(cross(d, e2), n) * inv, dot(cross(e1, d), n) * inv);
}

// The same at the point y on the triangle's plane (a light sample drawn by solid angle).
vec3 triangle_emission_at(uint tri, vec3 y) {
  if (!has_feature(kFeatureTextures)) return vec3(materials[triangle_at(tri).material].emission);
  vec2 b = barycentric_at(tri, y);
  return triangle_emission(tri, b.x, b.y);
}

#endif  // PT_TEXTURE_GLSL
