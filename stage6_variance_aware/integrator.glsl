// stage6_variance_aware: beyond the article, stage5's MIS with three refinements that lower
// its variance (docs/stage6_variance_aware.md): the MIS weights count each strategy by how
// well a pilot saw it estimate (variance-aware MIS, Grittmann et al. 2019: mis_pilot.glsl,
// pilot.cpp); Russian roulette applies after the emission a ray finds, so both strategies'
// shares of a vertex's direct light end together, and a path it ends traces its last ray only
// where that ray may find emission; the roulette reads the path weight without glass's
// 1 / eta^2, and its square root (roulette_after_emission.glsl). This file is stage5's plus
// those: `diff stage5_mis/integrator.glsl stage6_variance_aware/integrator.glsl`.
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
#include "stage6_variance_aware/roulette_after_emission.glsl"
#include "stage6_variance_aware/mis_pilot.glsl"

// The power heuristic's weight of a sample drawn with pdf `mine` against the other
// strategy's pdf `other` for its direction: defined in common/kernel/mis.glsl.
float power_heuristic(float mine, float other);

vec3 Li(Ray ray) {
  vec3 L = vec3(0.0f);     // radiance gathered along the path
  vec3 beta = vec3(1.0f);  // path throughput: the product of the bounces' weights
  bool after_delta = false;  // the last bounce was a delta (mirror, glass)
  // The refractions' eta^2 along the path: beta * eta_scale is the throughput without the
  // radiance scale 1 / eta^2 of entering glass, which leaving it undoes (pbrt-v4's etaScale).
  float eta_scale = 1.0f;
  // The vertex whose BSDF sample made `ray`: its point, its normal on the side the light
  // came from, and the pdf of that sample (solid angle), to weigh the emission it finds.
  vec3 from_p = vec3(0.0f);
  vec3 from_n = vec3(0.0f, 0.0f, 1.0f);
  float bsdf_pdf = 0.0f;
  float from_scale = 1.0f;  // that vertex's factor on the light pdf (mis_light_scale)
  MisPilot pilot = mis_pilot_start();  // the pilot's sums (pilot passes only)
  // Russian roulette's verdict on the path beyond `ray`'s hit: 1 / p to go on, 0 to end
  // after the emission that `ray` finds (drawn below, before the ray is traced).
  float survive = 1.0f;
  for (uint depth = 0u;; depth++) {
    // A path that the roulette has ended traces its last ray only if it might find emission.
    if (survive == 0.0f && !may_find_emission(ray)) break;
    Hit hit = intersect_scene(ray, kInfinity);
    // Emission in full where no light sample could have found it: on camera rays and after
    // delta bounces; elsewhere weighed against the light sample that could have.
    bool in_full = depth == 0u || after_delta;
    if (hit.kind == kPrimNone) {
      // The sky is a light too: weighed against sampling it as one.
      vec3 sky = beta * sky_radiance(ray.dir);
      float w = in_full ? 1.0f : power_heuristic(bsdf_pdf, from_scale * sky_light_pdf(from_n, ray.dir));
      L += sky * w;
      pilot = mis_pilot_found(pilot, sky);
      break;
    }
    Surface surface = surface_at(ray, hit);
    Material material = surface_material(surface);
    vec3 Le = emitted_radiance(material, surface.front);
    if (max_component(Le) > 0.0f) {
      float w = in_full ? 1.0f : power_heuristic(bsdf_pdf, from_scale * light_pdf(from_p, ray.dir, hit, length(surface.p - from_p)));
      L += beta * Le * w;
    }
    pilot = mis_pilot_found(pilot, beta * Le);
    // The depth cap, or the roulette's verdict (drawn before this ray was traced, below),
    // ends the path after the emission its last ray found.
    if (at_depth_cap(depth) || survive == 0.0f) break;
    beta *= survive;  // the roulette's 1 / p, after the emission this ray found

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
      eta_scale *= bounce.eta2;
      after_delta = true;
    } else {
      // The light sample: direct light as in stage4, weighed against the BSDF sample that
      // could have found the same point (a point light is a delta: the light sample only).
      // Triangles are placed by the solid angle they subtend: light_pdf is that pdf.
      // (Rough glass sees lights on both sides: light_sample_normal, bsdf_toward.)
      float scale = mis_light_scale(lobe);
      vec3 light_n = light_sample_normal(lobe, n);
      LightSample ls = sample_light_by(surface.p, light_n, kTriangleBySolidAngle);
      BsdfToward b = bsdf_toward(lobe, material, wo, frame, surface, ls.wi);  // f and its cosine
      vec3 direct = vec3(0.0f);  // what the light sample alone finds (the pilot's X_l)
      if (b.cos > 0.0f && max_component(b.f * ls.weight) > 0.0f &&
          !occluded(surface.p, surface.n, ls)) {
        direct = beta * b.f * ls.weight * b.cos;
        float pdf_bsdf = bsdf_pdf_toward(lobe, material, wo, frame, surface, ls.wi);  // lobe_pdf, or folded
        float w = ls.pdf > 0.0f ? power_heuristic(scale * ls.pdf, pdf_bsdf) : 1.0f;
        L += direct * w;
      }
      // The pilot's X_l: what a BSDF sample could also find (a delta light's share is not).
      pilot = mis_pilot_vertex(pilot, lobe, ls.pdf > 0.0f ? direct : vec3(0.0f));
      // The BSDF sample, as in stage3 (Eq. 4): it continues the path, and the emission it
      // finds at the next hit counts with its weight (above).
      LobeSample s = sample_lobe(lobe, material, wo, lobe_numbers(lobe));
      vec3 weight = eval_lobe(lobe, material, wo, s.wi) * lobe_cos(lobe, s.wi) / s.pdf;
      if (ends_at_zero_pdf(s.pdf, weight)) break;  // never divide by a zero pdf
      wi = s.wi;
      beta *= weight;
      eta_scale *= lobe_eta2(lobe, material, wi);
      after_delta = false;
      from_p = surface.p;
      from_n = light_n;
      bsdf_pdf = sampled_pdf(s, lobe, material, wo, frame, surface);  // s.pdf, or the folded pdf
      from_scale = scale;
    }

    ray = spawn_ray(surface.p, surface.n, shading_to_world(frame, surface, wi));
    // Russian roulette for the path beyond the new ray's hit, applied after the emission
    // that ray finds (above), not before the ray as in stages 2-5: the two strategies'
    // shares of one vertex's direct light then survive or end together, as their MIS weights
    // assume. It is drawn here, with the number and the weight it would have at the next hit
    // (nothing is drawn in between), so that a path it ends traces its last ray only where
    // that ray may find emission (may_find_emission, above).
    survive = 1.0f;  // at the depth cap the path ends before the roulette would draw
    if (depth + 1u != params.depth_cap) survive = russian_roulette(roulette_weight(beta, eta_scale), params.roulette);
  }
  return pilot_mode() == 0u ? L : mis_pilot_found(pilot, vec3(0.0f)).sums;
}
