// stage2_montecarlo: Monte Carlo path tracing as the article builds it (section "Алгоритм
// трассировки путей по методу Монте Карло", Eq. 3): at every hit add the emission, then
// continue in ONE new direction (N = 1), drawn uniformly over the hemisphere for diffuse
// and glossy surfaces, or the reflected/refracted direction of mirrors and glass; paths
// end by Russian roulette. Written in the GLSL/C++ subset: both backends run this file.
#include "common/kernel/sampler.glsl"
#include "common/kernel/camera.glsl"
#include "common/kernel/intersect.glsl"
#include "common/kernel/texture.glsl"
#include "common/kernel/sampling.glsl"
#include "common/kernel/bsdf.glsl"
#include "common/kernel/shading_normal.glsl"
#include "common/kernel/spawn.glsl"
#include "common/kernel/roulette.glsl"
#include "common/kernel/environment.glsl"

vec3 Li(Ray ray) {
  vec3 L = vec3(0.0f);     // radiance gathered along the path
  vec3 beta = vec3(1.0f);  // path throughput: the product of the bounces' weights
  for (uint depth = 0u;; depth++) {
    if (at_depth_cap(depth)) break;  // a safety net far beyond what roulette reaches
    Hit hit = intersect_scene(ray, kInfinity);
    if (hit.kind == kPrimNone) {  // the sky: --sky's colour, or the environment map
      L += beta * sky_radiance(ray.dir);
      break;
    }
    Surface surface = surface_at(ray, hit);
    Material material = surface_material(surface);
    // Le: in the article's Eq. (3) every hit adds its emission.
    L += beta * emitted_radiance(material, surface.front);

    // Directions in the frame of the side the ray came from: surfaces reflect on both sides.
    // (Its normal is the shading normal where the triangle has one: shading_normal.glsl.)
    Frame frame = shading_frame(surface, ray.dir);
    vec3 wo = frame_to_local(frame, -ray.dir);
    uint lobe = choose_lobe(material, wo, sample_1d());
    vec3 wi;
    if (is_delta_lobe(lobe)) {  // mirror or glass: the one direction they send light
      DeltaBounce bounce = sample_delta_lobe(lobe, material, wo, surface.front, sample_1d());
      wi = bounce.wi;
      beta *= bounce.weight;
    } else {
      // Eq. (3) with N = 1: one direction uniform over the hemisphere, weighted
      // (2 pi / N) f cos, 2 pi = 1 / pdf (erratum 1: the article prints 1 / (2 pi N)).
      // Rough glass transmits too: uniform over the sphere, f |cos| 4 pi (bsdf.glsl).
      wi = sample_uniform_bounce(lobe, sample_2d());
      beta *= uniform_lobe_weight(lobe, eval_lobe(lobe, material, wo, wi), wi);
    }

    float survive = russian_roulette(beta, params.roulette);
    if (survive == 0.0f) break;
    beta *= survive;
    ray = spawn_ray(surface.p, surface.n, shading_to_world(frame, surface, wi));
  }
  return L;
}
