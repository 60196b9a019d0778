// Shading normals (issue #46; beyond the article, whose surfaces are flat): glTF's vertex
// normals (NORMAL) interpolated over a triangle and perturbed by its normal map, and the rule
// that keeps them from darkening facets or leaking light (docs/shading_normals.md). Only
// triangles flagged kTriangleShadingNormals run any of it; every other surface (and every
// kernel without kFeatureShadingNormals) gets exactly the geometric frame of before.
#ifndef PT_SHADING_NORMAL_GLSL
#define PT_SHADING_NORMAL_GLSL

#include "common/kernel/intersect.glsl"
#include "common/kernel/texture_lookup.glsl"
#include "common/kernel/sampling.glsl"
#include "common/kernel/bsdf.glsl"

// The least cosine between the shading normal and the direction the ray came back along:
// a shading normal that faces away from the viewer is bent toward it until it is this high.
const float kShadingMinCos = 0.01f;

// The geometric normal on the side the ray arrived from.
vec3 side_normal(Surface surface) {
  return surface.front ? surface.n : -surface.n;
}

// The shading normal of a flagged triangle at the surface point, on its front side: the
// vertex normals interpolated and, where its material has a normal map, the map's
// tangent-space normal (x, y scaled by normalTexture.scale, as glTF says) in the frame of the
// interpolated normal, tangent (made orthogonal to it) and bitangent.
vec3 front_shading_normal(Surface surface) {
  TriangleShading s = triangle_shading[surface.triangle];
  float b0 = 1.0f - surface.b1 - surface.b2;
  vec3 n = b0 * vec3(s.normal0) + surface.b1 * vec3(s.normal1) + surface.b2 * vec3(s.normal2);
  float n_len = length(n);
  if (!(n_len > 1e-6f)) return surface.n;  // opposite vertex normals cancel: the face's
  n = n / n_len;
  if (!has_feature(kFeatureTextures)) return n;
  MaterialTextures mt = material_textures[surface.material];
  if (mt.enabled == 0u || mt.normal == kNoTexture) return n;
  vec3 t = b0 * vec3(s.tangent0) + surface.b1 * vec3(s.tangent1) + surface.b2 * vec3(s.tangent2);
  t = t - dot(t, n) * n;
  float t_len = length(t);
  if (!(t_len > 1e-6f)) return n;  // a tangent along the normal: no frame to read the map in
  t = t / t_len;
  float handedness = b0 * s.handedness0 + surface.b1 * s.handedness1 + surface.b2 * s.handedness2;
  vec3 b = cross(n, t);
  if (handedness < 0.0f) b = -b;
  vec2 uv = slot_uv(mt.tex_coord_sets, kSlotNormal, vec3(mt.normal_s), vec3(mt.normal_t),
                    triangle_attributes[surface.triangle], surface.b1, surface.b2);
  vec4 texel = texture_lookup(mt.normal, uv, false);
  vec3 m = vec3((2.0f * texel.x - 1.0f) * mt.normal_scale, (2.0f * texel.y - 1.0f) * mt.normal_scale,
                2.0f * texel.z - 1.0f);
  vec3 mapped = m.x * t + m.y * b + m.z * n;
  float len = length(mapped);
  return len > 1e-6f ? mapped / len : n;
}

// The shading normal on the side the ray `dir` arrived from, bent toward the viewer where it
// faces away (Cycles' "ensure valid reflection", done on the view direction): within the
// plane of the normal and the view direction wo, it is raised until cos(wo, normal) is
// kShadingMinCos, so that wo is always above it and no lobe is black there.
vec3 shading_normal(Surface surface, vec3 dir) {
  vec3 ns = front_shading_normal(surface);
  if (!surface.front) ns = -ns;
  vec3 wo = -dir;
  float c = dot(ns, wo);
  if (c >= kShadingMinCos) return ns;
  vec3 across = ns - c * wo;  // the part of ns across wo
  float len = length(across);
  if (!(len > 1e-6f)) return side_normal(surface);
  return kShadingMinCos * wo + sqrt(1.0f - kShadingMinCos * kShadingMinCos) * (across / len);
}

// The frame the BSDF is evaluated and sampled in at a surface hit by a ray along `dir`: the
// shading normal's, or the geometric normal's on the side the ray came from.
Frame shading_frame(Surface surface, vec3 dir) {
  if (!surface.shaded) return make_frame(side_normal(surface));
  return make_frame(shading_normal(surface, dir));
}

// A direction of the shading frame in world space, on the side of the GEOMETRIC surface its
// lobe meant (above for reflection, wi.z > 0; below for transmission): one that the tilt of
// the shading normal put on the other side is reflected across the geometric tangent plane.
// The reflection keeps solid angle, so the bounce's weight f cos / pdf stays unbiased for the
// folded BSDF f_eff(w) cos_g(w) = f(w) cos_s(w)+ + f(R w) cos_s(R w)+ (bsdf_toward below),
// whose integral is the lobe's albedo in the shading frame: no leak, no loss.
vec3 shading_to_world(Frame frame, Surface surface, vec3 wi) {
  vec3 w = frame_to_world(frame, wi);
  if (!surface.shaded) return w;
  vec3 n = side_normal(surface);
  float cos_g = dot(w, n);
#ifndef PT_BENCH_NO_FOLD  // set only by a bench build (bench/cycles/gltf_residuals.py): no fold
  if ((cos_g > 0.0f) != (wi.z > 0.0f)) w = w - 2.0f * cos_g * n;
#endif
  return w;
}

// A light sample's BSDF value f and cosine, for the light's contribution f Le cos / pdf: in
// the geometric frame, eval_lobe and wi.z; with a shading normal, the folded BSDF f_eff and
// the geometric cosine (zero below the geometric surface, where the light cannot be seen).
struct BsdfToward {
  vec3 f;     // the BSDF toward the light
  float cos;  // the cosine it is weighted with
};

// Whether a lobe sends light below its surface too (rough glass: lobe_cos is |cos| there).
bool sees_below(uint lobe) { return lobe_cos(lobe, vec3(0.0f, 0.0f, -1.0f)) > 0.0f; }

BsdfToward bsdf_toward(uint lobe, Material m, vec3 wo, Frame frame, Surface surface, vec3 w) {
  vec3 wl = frame_to_local(frame, w);
  if (!surface.shaded) return BsdfToward(eval_lobe(lobe, m, wo, wl), lobe_cos(lobe, wl));
  vec3 n = side_normal(surface);
  float cos_g = dot(w, n);
  // A lobe that transmits (rough glass) sees both sides: w below the geometric surface is
  // reached from the shading frame's lower hemisphere, and folded from its upper one.
  bool above = cos_g > 0.0f;
  if (!(abs(cos_g) > 1e-20f) || (!above && !sees_below(lobe))) {
    return BsdfToward(vec3(0.0f), 0.0f);
  }
  vec3 wr = frame_to_local(frame, w - 2.0f * cos_g * n);  // the folded partner R w
  vec3 f_cos = vec3(0.0f);
  if ((wl.z > 0.0f) == above && wl.z != 0.0f) f_cos += eval_lobe(lobe, m, wo, wl) * abs(wl.z);
#ifndef PT_BENCH_NO_FOLD
  if ((wr.z > 0.0f) == above && wr.z != 0.0f) f_cos += eval_lobe(lobe, m, wo, wr) * abs(wr.z);
#endif
  return BsdfToward(f_cos / abs(cos_g), abs(cos_g));
}
// The BSDF sample's pdf for direction w (world), as MIS weighs a light sample against it:
// lobe_pdf in the geometric frame; with a shading normal, the folded pdf pdf(w) + pdf(R w)
// of the directions shading_to_world sends to w.
float bsdf_pdf_toward(uint lobe, Material m, vec3 wo, Frame frame, Surface surface, vec3 w) {
  vec3 wl = frame_to_local(frame, w);
  if (!surface.shaded) return lobe_pdf(lobe, m, wo, wl);
  vec3 n = side_normal(surface);
  float cos_g = dot(w, n);
  bool above = cos_g > 0.0f;
  if (!(abs(cos_g) > 0.0f) || (!above && !sees_below(lobe))) return 0.0f;
  vec3 wr = frame_to_local(frame, w - 2.0f * cos_g * n);
  float pdf = 0.0f;
  if ((wl.z > 0.0f) == above && wl.z != 0.0f) pdf += lobe_pdf(lobe, m, wo, wl);
#ifndef PT_BENCH_NO_FOLD
  if ((wr.z > 0.0f) == above && wr.z != 0.0f) pdf += lobe_pdf(lobe, m, wo, wr);
#endif
  return pdf;
}

// The pdf that MIS weighs the emission a BSDF sample finds with: the sample's own pdf, or,
// with a shading normal, the folded pdf of the direction it was sent in.
float sampled_pdf(LobeSample s, uint lobe, Material m, vec3 wo, Frame frame, Surface surface) {
  if (!surface.shaded) return s.pdf;
  return bsdf_pdf_toward(lobe, m, wo, frame, surface, shading_to_world(frame, surface, s.wi));
}

#endif  // PT_SHADING_NORMAL_GLSL
