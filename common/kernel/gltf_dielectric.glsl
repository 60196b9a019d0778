// The dielectric of the glTF 2.0 metallic-roughness material (the specification's Appendix B,
// fresnel_mix, with KHR_materials_specular's weight w and colour): a GGX specular layer over
// a Lambert base of the base colour, mixed by Schlick's Fresnel F at the microfacet normal h,
//   f = (1 - w max(F(v.h))) base / pi + w F(v.h) D G2 / (4 |n.l| |n.v|).
// Beyond the article (docs/gltf_material.md). Included by bsdf.glsl, which dispatches to it.
#ifndef PT_GLTF_DIELECTRIC_GLSL
#define PT_GLTF_DIELECTRIC_GLSL

float largest_channel(vec3 v) {
  return max(max(v.x, v.y), v.z);
}

// Schlick's Fresnel of the layer at cos_theta = v.h: F0 = m.specular_f0, the ior's
// ((ior - 1) / (ior + 1))^2 times specularColorFactor (at most 1), made on load.
vec3 layer_fresnel(Material m, float cos_theta) {
  return schlick_fresnel(vec3(m.specular_f0), cos_theta);
}

// The share of light the layer leaves to the base: 1 - w max(F).
float base_share(Material m, vec3 F) {
  return max(1.0f - m.specular * largest_channel(F), 0.0f);
}

// f of the dielectric for wo, wi in the upper hemisphere. A smooth layer (alpha below
// kGgxMirrorAlpha) is a delta, sampled by sample_smooth_layer and never evaluated: only
// the base remains.
vec3 dielectric_brdf(Material m, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return vec3(0.0f);
  vec3 h = normalize(wo + wi);
  vec3 F = layer_fresnel(m, dot(wo, h));
  vec3 base = vec3(m.base_color) * (base_share(m, F) / kPi);
  if (m.alpha < kGgxMirrorAlpha) return base;
  float alpha = m.alpha;
  return base + F * (m.specular * ggx_d(h, alpha) * ggx_g2(wo, wi, alpha) / (4.0f * wo.z * wi.z));
}

// The probability of sampling the layer rather than the base: each in proportion to what
// it reflects, estimated with Fresnel at n.v: w max(F(n.v)) for the layer, the base's
// share times its largest albedo for the base. A black base leaves the layer alone (1).
float layer_probability(Material m, vec3 wo) {
  vec3 F = layer_fresnel(m, wo.z);
  float layer = m.specular * largest_channel(F);
  float base = base_share(m, F) * largest_channel(vec3(m.base_color));
  return layer + base > 0.0f ? layer / (layer + base) : 0.5f;
}

// The pdf of the rough dielectric's sampling: the mixture of the two layers' pdfs.
float dielectric_pdf(Material m, vec3 wo, vec3 wi) {
  float p = layer_probability(m, wo);
  return p * ggx_vndf_pdf(wo, wi, m.alpha) + (1.0f - p) * cosine_hemisphere_pdf(wi.z);
}

// A direction for the rough dielectric (stage3, Eq. 4): the layer with probability p (GGX
// visible normals), else the base (cosine). u.x picks the layer and, stretched back onto
// [0, 1), draws the direction within it. The pdf is the mixture's: either layer could have
// drawn wi.
LobeSample sample_dielectric(Material m, vec3 wo, vec2 u) {
  float p = layer_probability(m, wo);
  vec3 wi;
  if (u.x < p) {
    vec3 h = sample_ggx_vndf(wo, m.alpha, vec2(min(u.x / p, kOneMinusEpsilon), u.y));
    wi = 2.0f * dot(wo, h) * h - wo;
  } else {
    wi = sample_cosine_hemisphere(vec2(min((u.x - p) / (1.0f - p), kOneMinusEpsilon), u.y));
  }
  return LobeSample(wi, dielectric_pdf(m, wo, wi));
}

// The glass part of a material with transmission between 0 and 1 (docs/gltf_material.md,
// "Partial transmission"): smooth glass (a delta) where the layer is smooth or the ior is
// 1, as make_gltf_material makes glass, else rough glass (whose ior surface_material made
// relative to the side the ray arrives from).
uint glass_part(Material m) {
  bool rough = has_feature(kFeatureRoughGlass) && m.alpha >= kGgxMirrorAlpha && m.ior != 1.0f;
  return rough ? kMaterialRoughGlass : kMaterialGlass;
}

// Which lobe a glTF material scatters by (choose_lobe): the conductor with probability
// metallic, else the dielectric, one non-delta lobe when its layer is rough; a smooth layer
// is a delta, so then u also picks the layer's mirror (probability p) or the base. With a
// transmission T between 0 and 1, the glass part takes the first T of what the conductor
// leaves, and the dielectric the rest (u stretched back onto [0, 1) for the smooth layer's
// choice). None of it looks at the direction that follows: each part's own pdf is the
// density of its sampling (stage5's MIS weights).
uint choose_gltf_lobe(Material m, vec3 wo, float u) {
  if (u < m.metallic) return m.alpha >= kGgxMirrorAlpha ? kMaterialConductor : kMaterialMirror;
  if ((has_feature(kFeatureGlass) || has_feature(kFeatureRoughGlass)) && m.transmission > 0.0f) {
    float v = (u - m.metallic) / (1.0f - m.metallic);
    if (v < m.transmission) return glass_part(m);
    if (m.alpha >= kGgxMirrorAlpha) return kMaterialDielectric;
    float w = min((v - m.transmission) / (1.0f - m.transmission), kOneMinusEpsilon);
    return w < layer_probability(m, wo) ? kLobeSmoothLayer : kLobeSmoothBase;
  }
  if (m.alpha >= kGgxMirrorAlpha) return kMaterialDielectric;
  float v = (u - m.metallic) / (1.0f - m.metallic);
  return v < layer_probability(m, wo) ? kLobeSmoothLayer : kLobeSmoothBase;
}

// The smooth layer's mirror bounce, picked with probability p: weight w F(n.v) / p.
DeltaBounce sample_smooth_layer(Material m, vec3 wo) {
  vec3 F = layer_fresnel(m, wo.z);
  return DeltaBounce(vec3(-wo.x, -wo.y, wo.z), F * (m.specular / layer_probability(m, wo)), 1.0f);
}

// The base under a smooth layer, picked with probability 1 - p: its f over 1 - p.
vec3 smooth_base_brdf(Material m, vec3 wo, vec3 wi) {
  return dielectric_brdf(m, wo, wi) / (1.0f - layer_probability(m, wo));
}

#endif  // PT_GLTF_DIELECTRIC_GLSL
