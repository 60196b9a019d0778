// The materials of CONTRACT.md as functions of local directions (z = the normal on the
// side the light arrives from): Lambertian diffuse, Schlick-Fresnel conductors (a perfect
// mirror, or GGX microfacets with Smith's height-correlated masking), smooth glass with
// exact dielectric Fresnel. f is the BRDF of Eq. (1); delta lobes are sampled, not evaluated.
#ifndef PT_BSDF_GLSL
#define PT_BSDF_GLSL

// Le of Eq. (1): a surface emits from its front face only (counter-clockwise winding, the
// geometric normal's side), or from both faces when its material is double-sided.
vec3 emitted_radiance(Material m, bool front) {
  return (front || m.emission.w > 0.0f) ? vec3(m.emission) : vec3(0.0f);
}

vec3 schlick_fresnel(vec3 f0, float cos_theta) {
  float m = clamp(1.0f - cos_theta, 0.0f, 1.0f);
  float m2 = m * m;
  return f0 + (vec3(1.0f) - f0) * (m2 * m2 * m);
}

// Unpolarised Fresnel reflectance of a smooth dielectric; eta = n_transmitted / n_incident.
// Returns 1 under total internal reflection.
float fresnel_dielectric(float cos_i, float eta) {
  cos_i = clamp(cos_i, 0.0f, 1.0f);
  float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0f) return 1.0f;
  float cos_t = sqrt(1.0f - sin2_t);
  float r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  float r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return 0.5f * (r_parl * r_parl + r_perp * r_perp);
}

// GGX (Trowbridge-Reitz) distribution of microfacet normals h (local, h.z > 0).
float ggx_d(vec3 h, float alpha) {
  float a2 = alpha * alpha;
  float c2 = h.z * h.z;
  float d = c2 * (a2 - 1.0f) + 1.0f;
  return a2 / (kPi * d * d);
}

// Smith's Lambda for GGX: the masking of direction w is 1 / (1 + Lambda(w)).
float ggx_lambda(vec3 w, float alpha) {
  float c2 = w.z * w.z;
  float t2 = max(0.0f, 1.0f - c2) / max(c2, 1e-30f);
  return 0.5f * (sqrt(1.0f + alpha * alpha * t2) - 1.0f);
}

// Height-correlated masking-shadowing G2(wo, wi).
float ggx_g2(vec3 wo, vec3 wi, float alpha) {
  return 1.0f / (1.0f + ggx_lambda(wo, alpha) + ggx_lambda(wi, alpha));
}

// The GGX conductor's BRDF for wo, wi in the upper hemisphere.
vec3 ggx_conductor_brdf(vec3 f0, float alpha, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return vec3(0.0f);
  vec3 h = normalize(wo + wi);
  vec3 F = schlick_fresnel(f0, dot(wo, h));
  return F * (ggx_d(h, alpha) * ggx_g2(wo, wi, alpha) / (4.0f * wo.z * wi.z));
}

vec3 lambert_brdf(vec3 albedo, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return vec3(0.0f);
  return albedo * (1.0f / kPi);
}

// Which lobe a surface scatters by: a mixed material (0 < metallic < 1) is the conductor
// with probability metallic, else the diffuse (CONTRACT.md); u is a uniform number.
uint choose_lobe(Material m, float u) {
  uint kind = m.kind.x;
  if (kind != kMaterialMixed) return kind;
  if (u >= m.params.x) return kMaterialDiffuse;
  return m.params.y > 0.0f ? kMaterialConductor : kMaterialMirror;
}

// f of a non-delta lobe (kMaterialDiffuse or kMaterialConductor).
vec3 eval_lobe(uint lobe, Material m, vec3 wo, vec3 wi) {
  if (lobe == kMaterialConductor) return ggx_conductor_brdf(vec3(m.base_color), m.params.y, wo, wi);
  return lambert_brdf(vec3(m.base_color), wo, wi);
}

bool is_delta_lobe(uint lobe) {
  return lobe == kMaterialMirror || lobe == kMaterialGlass;
}

// A delta bounce: the one direction a mirror or glass sends the light, and the weight
// f cos / pdf it carries (the delta cancels).
struct DeltaBounce {
  vec3 wi;      // local direction
  vec3 weight;  // throughput factor
};

// Mirror: reflection about the normal, weighted by Schlick's Fresnel with F0 = base colour.
DeltaBounce sample_mirror(Material m, vec3 wo) {
  return DeltaBounce(vec3(-wo.x, -wo.y, wo.z), schlick_fresnel(vec3(m.base_color), wo.z));
}

// Glass: reflect with probability F, else refract (the weight F / F = 1 or
// (1 - F) / (1 - F) times the tint and the radiance scale 1 / eta^2). entering: wo is on
// the outside (front) of the surface.
DeltaBounce sample_glass(Material m, vec3 wo, bool entering, float u) {
  float eta = entering ? m.params.w : 1.0f / m.params.w;
  float F = fresnel_dielectric(wo.z, eta);
  if (u < F) return DeltaBounce(vec3(-wo.x, -wo.y, wo.z), vec3(1.0f));
  float sin2_t = max(0.0f, 1.0f - wo.z * wo.z) / (eta * eta);
  float cos_t = sqrt(max(0.0f, 1.0f - sin2_t));
  vec3 wi = vec3(-wo.x / eta, -wo.y / eta, -cos_t);
  return DeltaBounce(wi, vec3(m.base_color) * (1.0f / (eta * eta)));
}

#endif  // PT_BSDF_GLSL
