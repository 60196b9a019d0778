// A rough dielectric for KHR_materials_transmission with roughness > 0 (kMaterialRoughGlass):
// Walter et al. 2007, "Microfacet models for refraction through rough surfaces", GGX D,
// Smith's height-correlated G2, exact dielectric Fresnel, reflection and refraction by the
// microfacet normal; sampled by GGX visible normals. Beyond the article (docs/gltf_material.md,
// "Rough transmission"). Included by bsdf.glsl, which dispatches to it.
#ifndef PT_ROUGH_DIELECTRIC_GLSL
#define PT_ROUGH_DIELECTRIC_GLSL

// Directions are local with wo.z > 0 (the side the ray arrives from), and eta = m.ior is
// relative: the index beyond the surface over the index on wo's side (surface_material
// inverts it on a back face). wi.z > 0 is reflection, wi.z < 0 refraction.

// The microfacet normal that refracts wo into wi (Walter's generalised half vector
// -(wo + eta wi), Eq. 16), turned to the upper side; the zero vector where it vanishes.
vec3 refraction_half_vector(vec3 wo, vec3 wi, float eta) {
  vec3 h = -(wo + eta * wi);
  float len2 = dot(h, h);
  if (!(len2 > 0.0f)) return vec3(0.0f);
  h = h * inversesqrt(len2);
  return h.z < 0.0f ? -h : h;
}

// f (radiance): reflection F D G2 / (4 |wo.z| |wi.z|) above; below, Walter's Eq. 21 for
// radiance with the relative eta, times the base colour (the tint):
//   (1 - F(wo.h)) D G2 |wo.h| |wi.h| / (|wo.z| |wi.z| (wo.h + eta wi.h)^2).
// (Walter's eta_o^2 over the same denominator in absolute indices: the 1 / eta^2 of
// radiance entering the denser side is in it, as in sample_glass's weight.)
vec3 rough_glass_bsdf(Material m, vec3 wo, vec3 wi) {
  if (!(wo.z > 0.0f) || wi.z == 0.0f) return vec3(0.0f);
  float eta = m.ior;
  float alpha = m.alpha;
  if (wi.z > 0.0f) {
    vec3 h = normalize(wo + wi);
    float F = fresnel_dielectric(dot(wo, h), eta);
    return vec3(F * ggx_d(h, alpha) * ggx_g2(wo, wi, alpha) / (4.0f * wo.z * wi.z));
  }
  vec3 h = refraction_half_vector(wo, wi, eta);
  float co = dot(wo, h);
  float ci = dot(wi, h);
  if (!(co > 0.0f) || !(ci < 0.0f)) return vec3(0.0f);  // no microfacet refracts wo into wi
  float F = fresnel_dielectric(co, eta);
  float denom = co + eta * ci;
  float t = (1.0f - F) * ggx_d(h, alpha) * ggx_g2(wo, wi, alpha) * (co * -ci) / (wo.z * -wi.z * denom * denom);
  return vec3(m.base_color) * t;
}

// The density (solid angle) with which sample_rough_glass draws wi: a visible normal h
// (G1(wo) D(h) (wo.h) / wo.z), then reflection with probability F(wo.h), Jacobian
// 1 / (4 wo.h), or refraction with probability 1 - F, Jacobian eta^2 |wi.h| / (wo.h + eta
// wi.h)^2. Both terms count wherever their direction lands: a reflection may leave below
// the surface and a refraction above it at grazing angles, and the weight f |cos| / pdf with
// this whole density stays unbiased there (the BSDF of wi's side over the mixture's pdf).
float rough_glass_pdf(Material m, vec3 wo, vec3 wi) {
  if (!(wo.z > 0.0f)) return 0.0f;
  float eta = m.ior;
  float alpha = m.alpha;
  float visible = 1.0f / ((1.0f + ggx_lambda(wo, alpha)) * wo.z);  // G1(wo) / wo.z
  float pdf = 0.0f;
  vec3 hr = wo + wi;
  if (dot(hr, hr) > 0.0f) {
    hr = normalize(hr);
    float co = dot(wo, hr);
    if (hr.z > 0.0f && co > 0.0f) pdf += fresnel_dielectric(co, eta) * visible * ggx_d(hr, alpha) * 0.25f;
  }
  vec3 ht = refraction_half_vector(wo, wi, eta);
  float co = dot(wo, ht);
  float ci = dot(wi, ht);
  if (ht.z > 0.0f && co > 0.0f && ci < 0.0f) {
    float denom = co + eta * ci;
    float jacobian = eta * eta * -ci / (denom * denom);
    pdf += (1.0f - fresnel_dielectric(co, eta)) * visible * ggx_d(ht, alpha) * co * jacobian;
  }
  return pdf;
}

// A direction for the rough dielectric from three uniform numbers: u.x, u.y draw the visible
// microfacet normal h (sample_ggx_vndf), u.z picks reflection about h with probability
// F(wo.h), else refraction through it (Snell's law about h, as sample_glass about n).
LobeSample sample_rough_glass(Material m, vec3 wo, vec3 u) {
  float eta = m.ior;
  vec3 h = sample_ggx_vndf(wo, m.alpha, vec2(u.x, u.y));
  float co = clamp(dot(wo, h), 0.0f, 1.0f);
  vec3 wi;
  if (u.z < fresnel_dielectric(co, eta)) {
    wi = 2.0f * co * h - wo;
  } else {
    float cos_t = sqrt(max(0.0f, cos2_transmitted(co, eta)));
    wi = (co / eta - cos_t) * h - wo / eta;
  }
  wi = normalize(wi);
  return LobeSample(wi, rough_glass_pdf(m, wo, wi));
}

// What a path's radiance scale changes by when it leaves along wi: eta^2 through a
// refraction (as DeltaBounce.eta2 of smooth glass), else 1.
float rough_glass_eta2(Material m, vec3 wi) {
  return wi.z < 0.0f ? m.ior * m.ior : 1.0f;
}

#endif  // PT_ROUGH_DIELECTRIC_GLSL
