// stage5_mis: beyond the article, multiple importance sampling of light and BSDF samples
// (Veach 1997; docs/stage5_mis.md). stage4 (Eq. 5) finds direct light only by light
// sampling, which loses to stage3's BSDF sampling under large lights and near edges. Here
// every non-delta hit takes both a light sample and a BSDF sample; each counts the
// emission it finds, weighted by the power heuristic of the two strategies' pdfs, so
// emission is counted on every bounce, once in expectation. This file is stage4's plus
// those weights: `diff stage4_direct_indirect/integrator.glsl stage5_mis/integrator.glsl`.
// Written in the GLSL/C++ subset: both backends run this file.
#include "common/kernel/sampler.glsl"
#include "common/kernel/camera.glsl"
#include "common/kernel/intersect.glsl"
#include "common/kernel/texture.glsl"
#include "common/kernel/sampling.glsl"
#include "common/kernel/bsdf.glsl"
#include "common/kernel/shading_normal.glsl"
#include "common/kernel/spawn.glsl"
#include "common/kernel/roulette.glsl"
#include "common/kernel/lights.glsl"

// The power heuristic's weight of a sample drawn with pdf `mine` against the other
// strategy's pdf `other` for its direction: defined in common/kernel/mis.glsl, or by
// labs/lab6.glsl in lab 6's build (cmake/Labs.cmake, kernel_definitions.glsl).
float power_heuristic(float mine, float other);

vec3 Li(Ray ray) {
  vec3 L = vec3(0.0f);     // radiance gathered along the path
  vec3 beta = vec3(1.0f);  // path throughput: the product of the bounces' weights
  bool after_delta = false;  // the last bounce was a delta (mirror, glass)
  // The vertex whose BSDF sample made `ray`: its point, its normal on the side the light
  // came from, and the pdf of that sample (solid angle), to weigh the emission it finds.
  vec3 from_p = vec3(0.0f);
  vec3 from_n = vec3(0.0f, 0.0f, 1.0f);
  float bsdf_pdf = 0.0f;
  for (uint depth = 0u;; depth++) {
    Hit hit = intersect_scene(ray, kInfinity);
    // Emission in full where no light sample could have found it: on camera rays and after
    // delta bounces; elsewhere weighed against the light sample that could have.
    bool in_full = depth == 0u || after_delta;
    if (hit.kind == kPrimNone) {
      // The sky is a light too: weighed against sampling it as one.
      float w = in_full ? 1.0f : power_heuristic(bsdf_pdf, sky_light_pdf(from_n, ray.dir));
      L += beta * sky_radiance(ray.dir) * w;
      break;
    }
    Surface surface = surface_at(ray, hit);
    Material material = surface_material(surface);
    vec3 Le = emitted_radiance(material, surface.front);
    if (max_component(Le) > 0.0f) {
      float w = in_full ? 1.0f : power_heuristic(bsdf_pdf, light_pdf(from_p, ray.dir, hit, length(surface.p - from_p)));
      L += beta * Le * w;
    }
    // The depth cap ends the path after the emission its last ray found: a path of N
    // bounces gets its direct light from both strategies, as stage4's from its one.
    if (at_depth_cap(depth)) break;  // a safety net far beyond what roulette reaches

    // Directions in the frame of the side the ray came from: surfaces reflect on both sides.
    // (Its normal is the shading normal where the triangle has one: shading_normal.glsl.)
    vec3 n = surface.front ? surface.n : -surface.n;
    Frame frame = shading_frame(surface, ray.dir);
    vec3 wo = frame_to_local(frame, -ray.dir);
    uint lobe = choose_lobe(material, wo, sample_1d());
    vec3 wi;
    if (is_delta_lobe(lobe)) {  // mirror or glass: the one direction they send light
      DeltaBounce bounce = sample_delta_lobe(lobe, material, wo, surface.front, sample_1d());
      wi = bounce.wi;
      beta *= bounce.weight;
      after_delta = true;
    } else {
      // The light sample: direct light as in stage4, weighed against the BSDF sample that
      // could have found the same point (a point light is a delta: the light sample only).
      // Triangles are placed by the solid angle they subtend: light_pdf is that pdf.
      // (Rough glass sees lights on both sides: light_sample_normal, bsdf_toward.)
      vec3 light_n = light_sample_normal(lobe, n);
      LightSample ls = sample_light_by(surface.p, light_n, kTriangleBySolidAngle);
      BsdfToward b = bsdf_toward(lobe, material, wo, frame, surface, ls.wi);  // f and its cosine
      if (b.cos > 0.0f && max_component(b.f * ls.weight) > 0.0f &&
          !occluded(surface.p, surface.n, ls)) {
        float pdf_bsdf = bsdf_pdf_toward(lobe, material, wo, frame, surface, ls.wi);  // lobe_pdf, or folded
        float w = ls.pdf > 0.0f ? power_heuristic(ls.pdf, pdf_bsdf) : 1.0f;
        L += beta * b.f * ls.weight * b.cos * w;
      }
      // The BSDF sample, as in stage3 (Eq. 4): it continues the path, and the emission it
      // finds at the next hit counts with its weight (above).
      LobeSample s = sample_lobe(lobe, material, wo, lobe_numbers(lobe));
      vec3 weight = eval_lobe(lobe, material, wo, s.wi) * lobe_cos(lobe, s.wi) / s.pdf;
      if (ends_at_zero_pdf(s.pdf, weight)) break;  // never divide by a zero pdf
      wi = s.wi;
      beta *= weight;
      after_delta = false;
      from_p = surface.p;
      from_n = light_n;
      bsdf_pdf = sampled_pdf(s, lobe, material, wo, frame, surface);  // s.pdf, or the folded pdf
    }

    float survive = russian_roulette(beta, params.roulette);
    if (survive == 0.0f) break;
    beta *= survive;
    ray = spawn_ray(surface.p, surface.n, shading_to_world(frame, surface, wi));
  }
  return L;
}
