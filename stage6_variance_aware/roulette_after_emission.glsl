// stage6_variance_aware (beyond the article): the pieces of its roulette. A path's roulette
// verdict is drawn before a ray is traced and applied after the emission that ray finds
// (integrator.glsl), so the two MIS strategies' shares of one vertex's direct light end
// together; a path the verdict ended traces that last ray only where may_find_emission says
// it might meet an emitter. The roulette reads roulette_weight instead of the path weight:
// glass's 1 / eta^2 taken out, and its square root. Docs: docs/stage6_variance_aware.md.
// Written in the GLSL/C++ subset: both backends run this file.
#ifndef PT_STAGE6_ROULETTE_AFTER_EMISSION_GLSL
#define PT_STAGE6_ROULETTE_AFTER_EMISSION_GLSL

#include "common/kernel/intersect.glsl"
#include "common/kernel/environment.glsl"
#include "common/kernel/roulette.glsl"

// At most this many entries of the light table are tried by may_find_emission; a scene
// with more emitters traces the ray instead.
const uint kMaxLightsTried = 16u;

// Whether a ray could find emission: false only where tracing it for certain finds none.
// That is so when the sky is black and no map lights it, no hole of an alpha mask can move
// the ray's origin (intersect_scene), and the ray meets none of the emitters: every surface
// that emits is in the light table (scene_lights.cpp), and the nearest hit of the full
// search, when it is an emitter, is a hit that emitter's own test finds, with the same ray
// and the same bits. Tries each emitter alone, so it costs a few triangle tests where the
// lights are few, and answers true (trace it) where they are many.
bool may_find_emission(Ray ray) {
  if (has_environment()) return true;
  if (has_feature(kFeatureSky) && (params.sky.x > 0.0f || params.sky.y > 0.0f || params.sky.z > 0.0f)) return true;
  if (has_feature(kFeatureAlphaMask) || params.light_count > kMaxLightsTried) return true;
  RayShear rs = make_ray_shear(ray.dir);
  Hit none = Hit(kInfinity, 0.0f, 0.0f, 0u, kPrimNone);
  for (uint i = 0u; i < params.light_count; i++) {
    Light light = lights[i];
    Hit hit = none;
    if (!has_feature(kFeatureSphereLights | kFeaturePointLights) || light.kind == kLightTriangle) {
      hit = hit_triangle(ray, rs, light.index, none);
    } else if (!has_feature(kFeaturePointLights) || light.kind == kLightSphere) {
      hit = hit_sphere(ray, light.index, none);
    }
    if (hit.kind != kPrimNone) return true;
  }
  return false;
}

// What the roulette reads in place of the path weight beta: beta times eta_scale, the
// refractions' eta^2 along the path (pbrt-v4's etaScale), so the radiance scale 1 / eta^2 of
// entering glass, which leaving it undoes, does not end most paths inside glass; and of that
// the square root, as Blender's Cycles takes it: a path ends later, when its weight has
// fallen further (p = 0.71 at weight 0.5, 0.32 at 0.1), which costs longer paths and pays
// in less variance.
vec3 roulette_weight(vec3 beta, float eta_scale) {
  return vec3(sqrt(max_component(beta * eta_scale)));
}

#endif  // PT_STAGE6_ROULETTE_AFTER_EMISSION_GLSL
