// The materials of the contract (README.md) as functions of local directions (z = the normal on the
// side the light arrives from): Lambertian diffuse, Schlick-Fresnel conductors (a perfect
// mirror, or GGX microfacets with Smith's height-correlated masking), smooth glass with
// exact dielectric Fresnel; glTF's dielectric, a GGX layer over a Lambert base
// (gltf_dielectric.glsl); and rough glass, GGX reflection and refraction (rough_dielectric.glsl). f is the BRDF of Eq. (1); delta lobes are sampled, not evaluated.
#ifndef PT_BSDF_GLSL
#define PT_BSDF_GLSL

#include "common/kernel/sampling.glsl"

// Le of Eq. (1): a surface emits from its front face only (counter-clockwise winding, the
// geometric normal's side), or from both faces when its material is double-sided.
vec3 emitted_radiance(Material m, bool front) {
  return (front || m.double_sided != 0u) ? vec3(m.emission) : vec3(0.0f);
}

vec3 schlick_fresnel(vec3 f0, float cos_theta) {
  float m = clamp(1.0f - cos_theta, 0.0f, 1.0f);
  float m2 = m * m;
  return f0 + (vec3(1.0f) - f0) * (m2 * m2 * m);
}

// Unpolarised Fresnel reflectance of a smooth dielectric; eta = n_transmitted / n_incident.
// Returns 1 under total internal reflection.
// cos_t^2 = 1 - sin_t^2 is formed as (eta^2 - 1 + cos_i^2) / eta^2, which keeps the small
// cos_i^2 of grazing angles that 1 - sin^2 would round away (docs/stability.md).
float cos2_transmitted(float cos_i, float eta) {
  return (eta * eta - 1.0f + cos_i * cos_i) / (eta * eta);
}

float fresnel_dielectric(float cos_i, float eta) {
  cos_i = clamp(cos_i, 0.0f, 1.0f);
  float cos2_t = cos2_transmitted(cos_i, eta);
  if (cos2_t <= 0.0f) return 1.0f;
  float cos_t = sqrt(cos2_t);
  float r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  float r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return 0.5f * (r_parl * r_parl + r_perp * r_perp);
}

// GGX (Trowbridge-Reitz) distribution of microfacet normals h (local, h.z > 0):
// alpha^2 / (pi (alpha^2 cos^2 + sin^2)^2). sin^2 is taken as x^2 + y^2, not 1 - cos^2,
// which cancels to nothing near the peak when alpha is small.
float ggx_d(vec3 h, float alpha) {
  float a2 = alpha * alpha;
  float d = a2 * h.z * h.z + (h.x * h.x + h.y * h.y);
  return a2 / (kPi * d * d);
}

// Smith's Lambda for GGX: the masking of direction w is 1 / (1 + Lambda(w)).
float ggx_lambda(vec3 w, float alpha) {
  float t2 = (w.x * w.x + w.y * w.y) / max(w.z * w.z, 1e-30f);  // tan^2 theta
  return 0.5f * (sqrt(1.0f + alpha * alpha * t2) - 1.0f);
}

// Height-correlated masking-shadowing G2(wo, wi), the glTF specification's (its Appendix B).
// PT_BENCH_SEPARABLE_MASKING is set only by a bench build (bench/cycles/gltf_residuals.py):
// Cycles 3.4's separable G1(wo) G1(wi), to measure what that difference does to an image.
float ggx_g2(vec3 wo, vec3 wi, float alpha) {
#ifdef PT_BENCH_SEPARABLE_MASKING
  return 1.0f / ((1.0f + ggx_lambda(wo, alpha)) * (1.0f + ggx_lambda(wi, alpha)));
#else
  return 1.0f / (1.0f + ggx_lambda(wo, alpha) + ggx_lambda(wi, alpha));
#endif
}

// The GGX conductor's BRDF for wo, wi in the upper hemisphere.
vec3 ggx_conductor_brdf(vec3 f0, float alpha, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return vec3(0.0f);
  vec3 h = normalize(wo + wi);
  vec3 F = schlick_fresnel(f0, dot(wo, h));
  return F * (ggx_d(h, alpha) * ggx_g2(wo, wi, alpha) / (4.0f * wo.z * wi.z));
}

// GGX visible-normal sampling (Heitz, "Sampling the GGX Distribution of Visible Normals",
// JCGT 2018): a microfacet normal h seen from wo, drawn in proportion to its projected
// area; the reflected direction's pdf is then G1(wo) D(h) / (4 wo.z).
vec3 sample_ggx_vndf(vec3 wo, float alpha, vec2 u) {
  // Stretch to the hemisphere configuration (alpha = 1).
  vec3 vh = normalize(vec3(alpha * wo.x, alpha * wo.y, wo.z));
  float len2 = vh.x * vh.x + vh.y * vh.y;
  vec3 t1 = len2 > 0.0f ? vec3(-vh.y, vh.x, 0.0f) * inversesqrt(len2) : vec3(1.0f, 0.0f, 0.0f);
  vec3 t2 = cross(vh, t1);
  // A point on the projected disk, squeezed onto the visible half.
  float r = sqrt(u.x);
  float phi = 2.0f * kPi * u.y;
  float p1 = r * cos(phi);
  float p2 = r * sin(phi);
  float s = 0.5f * (1.0f + vh.z);
  p2 = (1.0f - s) * sqrt(max(0.0f, 1.0f - p1 * p1)) + s * p2;
  vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
  // Unstretch.
  return normalize(vec3(alpha * nh.x, alpha * nh.y, max(0.0f, nh.z)));
}

// The inverse of sample_ggx_vndf: the u that gives the microfacet normal h seen from wo.
vec2 invert_ggx_vndf(vec3 wo, float alpha, vec3 h) {
  vec3 vh = normalize(vec3(alpha * wo.x, alpha * wo.y, wo.z));
  float len2 = vh.x * vh.x + vh.y * vh.y;
  vec3 t1 = len2 > 0.0f ? vec3(-vh.y, vh.x, 0.0f) * inversesqrt(len2) : vec3(1.0f, 0.0f, 0.0f);
  vec3 t2 = cross(vh, t1);
  // Stretch h back to the hemisphere configuration and read its disk coordinates.
  vec3 nh = normalize(vec3(h.x / alpha, h.y / alpha, h.z));
  float p1 = dot(nh, t1);
  float s = 0.5f * (1.0f + vh.z);
  float p2 = (dot(nh, t2) - (1.0f - s) * sqrt(max(0.0f, 1.0f - p1 * p1))) / s;
  float phi = atan(p2, p1);
  if (phi < 0.0f) phi += 2.0f * kPi;
  return vec2(p1 * p1 + p2 * p2, phi / (2.0f * kPi));
}

// The pdf (solid angle) of wi = reflect(-wo, h) with h from sample_ggx_vndf.
float ggx_vndf_pdf(vec3 wo, vec3 wi, float alpha) {
  vec3 h = wo + wi;
  if (wo.z <= 0.0f || dot(h, h) == 0.0f) return 0.0f;
  h = normalize(h);
  if (h.z <= 0.0f) return 0.0f;
  float g1 = 1.0f / (1.0f + ggx_lambda(wo, alpha));
  return g1 * ggx_d(h, alpha) / (4.0f * wo.z);
}

vec3 lambert_brdf(vec3 albedo, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return vec3(0.0f);
  return albedo * (1.0f / kPi);
}

// A direction drawn for a non-delta lobe in proportion to (roughly) f cos, and its pdf
// (stage3, Eq. 4: importance sampling): cosine for diffuse, GGX visible normals for metal.
struct LobeSample {
  vec3 wi;    // local direction (may point below the surface: then f = 0)
  float pdf;  // solid-angle density of wi
};

// A delta bounce: the one direction a mirror or glass sends the light, and the weight
// f cos / pdf it carries (the delta cancels).
struct DeltaBounce {
  vec3 wi;      // local direction
  vec3 weight;  // throughput factor
  float eta2;   // eta^2 after a refraction, whose weight holds radiance's 1 / eta^2; else 1
};

// The glTF material's dielectric (a specular layer over a base), for glTF files.
#include "common/kernel/gltf_dielectric.glsl"
// The rough dielectric (KHR_materials_transmission with roughness), for glTF files.
#include "common/kernel/rough_dielectric.glsl"

// Which lobe a surface scatters by: a mixed material (0 < metallic < 1) is the conductor
// with probability metallic, else the diffuse (the contract (README.md)); u is a uniform number.
// A conductor with alpha below kGgxMirrorAlpha scatters as the perfect mirror. A glTF
// material (kMaterialDielectric) also reads wo: it picks a smooth layer by its Fresnel.
uint choose_lobe(Material m, vec3 wo, float u) {
  uint kind = m.kind;
  if (has_feature(kFeatureConductor) && kind == kMaterialConductor) {
    return m.alpha < kGgxMirrorAlpha ? kMaterialMirror : kind;  // alpha ~ 0: a mirror
  }
  if (has_feature(kFeatureDielectric) && kind == kMaterialDielectric) return choose_gltf_lobe(m, wo, u);
  if (!has_feature(kFeatureMixed) || kind != kMaterialMixed) return kind;
  if (u >= m.metallic) return kMaterialDiffuse;
  return m.alpha >= kGgxMirrorAlpha ? kMaterialConductor : kMaterialMirror;
}

// f of a non-delta lobe (kMaterialDiffuse, kMaterialConductor, kMaterialDielectric,
// kLobeSmoothBase or kMaterialRoughGlass, the one that also transmits: wi.z < 0).
vec3 eval_lobe(uint lobe, Material m, vec3 wo, vec3 wi) {
  if (has_feature(kFeatureRoughGlass) && lobe == kMaterialRoughGlass) return rough_glass_bsdf(m, wo, wi);
  if (has_feature(kFeatureConductor) && lobe == kMaterialConductor) return ggx_conductor_brdf(m.base_color, m.alpha, wo, wi);
  if (has_feature(kFeatureDielectric)) {
    if (lobe == kMaterialDielectric) return dielectric_brdf(m, wo, wi);
    if (lobe == kLobeSmoothBase) return smooth_base_brdf(m, wo, wi);
  }
  return lambert_brdf(m.base_color, wo, wi);
}

// A direction for a lobe that reflects only (the rough dielectric needs a third number:
// the overload below).
LobeSample sample_lobe(uint lobe, Material m, vec3 wo, vec2 u) {
  if (has_feature(kFeatureConductor) && lobe == kMaterialConductor) {
    float alpha = m.alpha;
    vec3 h = sample_ggx_vndf(wo, alpha, u);
    vec3 wi = 2.0f * dot(wo, h) * h - wo;
    return LobeSample(wi, ggx_vndf_pdf(wo, wi, alpha));
  }
  if (has_feature(kFeatureDielectric) && lobe == kMaterialDielectric) return sample_dielectric(m, wo, u);
  vec3 wi = sample_cosine_hemisphere(u);
  return LobeSample(wi, cosine_hemisphere_pdf(wi.z));
}

// A direction for any non-delta lobe from the numbers lobe_numbers(lobe) drew: the rough
// dielectric reads all three, every other lobe the first two.
LobeSample sample_lobe(uint lobe, Material m, vec3 wo, vec3 u) {
  if (has_feature(kFeatureRoughGlass) && lobe == kMaterialRoughGlass) return sample_rough_glass(m, wo, u);
  return sample_lobe(lobe, m, wo, vec2(u.x, u.y));
}

// The uniform numbers a lobe's sample_lobe reads: a 2-D sample, and for the rough
// dielectric a third number after it (its choice between reflection and refraction), so
// that a scene without one draws exactly the numbers it drew before.
vec3 lobe_numbers(uint lobe) {
  vec2 u = sample_2d();
  float v = has_feature(kFeatureRoughGlass) && lobe == kMaterialRoughGlass ? sample_1d() : 0.0f;
  return vec3(u.x, u.y, v);
}

// The |cos| of Eq. (1) that f multiplies for direction wi: the rough dielectric sees both
// sides of its surface; every other lobe only the side the ray came from (clamped to 0).
float lobe_cos(uint lobe, vec3 wi) {
  if (has_feature(kFeatureRoughGlass) && lobe == kMaterialRoughGlass) return abs(wi.z);
  return max(wi.z, 0.0f);
}

// The normal a light sample is drawn about (lights.glsl sample_sky, sky_light_pdf): n, or
// for a lobe that transmits the zero vector, which asks for the whole sphere of the sky.
vec3 light_sample_normal(uint lobe, vec3 n) {
  if (has_feature(kFeatureRoughGlass) && lobe == kMaterialRoughGlass) return vec3(0.0f);
  return n;
}

// What a non-delta bounce to wi changes the path's radiance scale by (eta^2 after a refraction;
// the tests' energy kept, R + eta^2 T, reads it).
float lobe_eta2(uint lobe, Material m, vec3 wi) {
  if (has_feature(kFeatureRoughGlass) && lobe == kMaterialRoughGlass) return rough_glass_eta2(m, wi);
  return 1.0f;
}

// Stage2's uniform direction for a lobe: the hemisphere (Eq. 3), or for a lobe that
// transmits the whole sphere, density 1 / (4 pi); and the weight f |cos| / pdf it carries.
vec3 sample_uniform_bounce(uint lobe, vec2 u) {
  if (!has_feature(kFeatureRoughGlass) || lobe != kMaterialRoughGlass) return sample_uniform_hemisphere(u);
  float z = 1.0f - 2.0f * u.x;
  float r = sqrt(max(0.0f, 1.0f - z * z));
  float phi = 2.0f * kPi * u.y;
  return vec3(r * cos(phi), r * sin(phi), z);
}

vec3 uniform_lobe_weight(uint lobe, vec3 f, vec3 wi) {
  if (!has_feature(kFeatureRoughGlass) || lobe != kMaterialRoughGlass) return uniform_bounce_weight(f, wi);
  return f * (abs(wi.z) * 4.0f * kPi);
}

float lobe_pdf(uint lobe, Material m, vec3 wo, vec3 wi) {
  if (has_feature(kFeatureRoughGlass) && lobe == kMaterialRoughGlass) return rough_glass_pdf(m, wo, wi);
  if (has_feature(kFeatureConductor) && lobe == kMaterialConductor) return ggx_vndf_pdf(wo, wi, m.alpha);
  if (has_feature(kFeatureDielectric) && lobe == kMaterialDielectric) return dielectric_pdf(m, wo, wi);
  return cosine_hemisphere_pdf(wi.z);
}

// Mirror: reflection about the normal, weighted by Schlick's Fresnel with F0 = base colour.
DeltaBounce sample_mirror(Material m, vec3 wo) {
  return DeltaBounce(vec3(-wo.x, -wo.y, wo.z), schlick_fresnel(m.base_color, wo.z), 1.0f);
}

// Glass: reflect with probability F, else refract (the weight F / F = 1 or
// (1 - F) / (1 - F) times the tint and the radiance scale 1 / eta^2). entering: wo is on
// the outside (front) of the surface.
DeltaBounce sample_glass(Material m, vec3 wo, bool entering, float u) {
  float eta = entering ? m.ior : 1.0f / m.ior;
  float F = fresnel_dielectric(wo.z, eta);
  if (u < F) return DeltaBounce(vec3(-wo.x, -wo.y, wo.z), vec3(1.0f), 1.0f);
  float cos_t = sqrt(max(0.0f, cos2_transmitted(min(abs(wo.z), 1.0f), eta)));
  vec3 wi = vec3(-wo.x / eta, -wo.y / eta, -cos_t);
  return DeltaBounce(wi, vec3(m.base_color) * (1.0f / (eta * eta)), eta * eta);
}

bool is_delta_lobe(uint lobe) {
  return (has_feature(kFeatureMirror) && lobe == kMaterialMirror) ||
         (has_feature(kFeatureGlass) && lobe == kMaterialGlass) ||
         (has_feature(kFeatureDielectric) && lobe == kLobeSmoothLayer);
}

// The bounce of a delta lobe (mirror, glass or a smooth layer); u picks reflection or
// refraction of glass.
DeltaBounce sample_delta_lobe(uint lobe, Material m, vec3 wo, bool front, float u) {
  if (has_feature(kFeatureDielectric) && lobe == kLobeSmoothLayer) return sample_smooth_layer(m, wo);
  if (!has_feature(kFeatureGlass) || lobe == kMaterialMirror) return sample_mirror(m, wo);
  return sample_glass(m, wo, front, u);
}

#endif  // PT_BSDF_GLSL
