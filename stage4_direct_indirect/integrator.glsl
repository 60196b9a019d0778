// stage4_direct_indirect: direct and indirect light (the article's section "Поддержка
// прямого/косвенного освещения" and light sampling, Eq. 5): at every non-delta hit, the
// direct light comes from a shadow ray to a point sampled on a light (soft shadows), the
// indirect light from one BRDF-sampled ray (as stage3) whose hit no longer adds emission.
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

vec3 Li(Ray ray) {
  vec3 L = vec3(0.0f);     // radiance gathered along the path
  vec3 beta = vec3(1.0f);  // path throughput: the product of the bounces' weights
  bool after_delta = false;  // the last bounce was a delta (mirror, glass)
  for (uint depth = 0u;; depth++) {
    if (at_depth_cap(depth)) break;  // a safety net far beyond what roulette reaches
    Hit hit = intersect_scene(ray, kInfinity);
    if (hit.kind == kPrimNone) {
      // The sky is a light too: after a non-delta bounce light sampling counted it.
      if (counts_emission(depth, after_delta)) L += beta * sky_radiance(ray.dir);
      break;
    }
    Surface surface = surface_at(ray, hit);
    Material material = surface_material(surface);
    // Le only where light sampling could not have found it (erratum 6): on camera rays and
    // after delta bounces; everywhere else it was counted as direct light already.
    if (counts_emission(depth, after_delta)) L += beta * emitted_radiance(material, surface.front);

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
      // Eq. (5), corrected (erratum 5): direct light f Le V cos_x cos_y / d^2 / pdf_A,
      // with the geometry term and the pdf inside the light sample's weight.
      // (Rough glass sees lights on both sides: light_sample_normal, bsdf_toward.)
      LightSample ls = sample_light(surface.p, light_sample_normal(lobe, n));
      BsdfToward b = bsdf_toward(lobe, material, wo, frame, surface, ls.wi);  // f and its cosine
      if (b.cos > 0.0f && max_component(b.f * ls.weight) > 0.0f &&
          !occluded(surface.p, surface.n, ls)) {
        L += beta * b.f * ls.weight * b.cos;
      }
      // Indirect light: one BRDF-sampled direction, as in stage3 (Eq. 4).
      LobeSample s = sample_lobe(lobe, material, wo, lobe_numbers(lobe));
      vec3 weight = eval_lobe(lobe, material, wo, s.wi) * lobe_cos(lobe, s.wi) / s.pdf;
      if (ends_at_zero_pdf(s.pdf, weight)) break;  // never divide by a zero pdf
      wi = s.wi;
      beta *= weight;
      after_delta = false;
    }

    float survive = russian_roulette(beta, params.roulette);
    if (survive == 0.0f) break;
    beta *= survive;
    ray = spawn_ray(surface.p, surface.n, shading_to_world(frame, surface, wi));
  }
  return L;
}
