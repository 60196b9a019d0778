// Punctual lights (glTF's KHR_lights_punctual; beyond the article, which has area lights
// only): point, spot and directional lights are deltas, so stage4's light sample (Eq. 5) is
// their one direction, and no BSDF sample ever hits them.
#ifndef PT_PUNCTUAL_LIGHT_GLSL
#define PT_PUNCTUAL_LIGHT_GLSL

#include "common/kernel/intersect.glsl"
#include "common/kernel/light_sample.glsl"

// A spot light's share of its intensity in the direction at cosine cos_d from its axis:
// full within the inner cone, none beyond the outer, and between them the square of the
// linear ramp in the cosine (KHR_lights_punctual's recommended falloff). A cone without a
// ramp (inner == outer: Blender's Spot Blend 0) has a hard edge, a step at the outer
// angle; its ramp's width is 0, which must not divide (0 / 0 on the edge).
float spot_falloff(PointLight l, float cos_d) {
  float ramp = l.cos_inner - l.cos_outer;
  if (!(ramp > 0.0f)) return cos_d >= l.cos_outer ? 1.0f : 0.0f;
  float t = clamp((cos_d - l.cos_outer) / ramp, 0.0f, 1.0f);
  return t * t;
}

// A punctual light: the light reaches p from one direction only (a delta), so the sample
// is that direction with pdf 0 and weight (incident radiance integrated) / pick. A point
// light of intensity I gives I / d^2, a spot light I falloff / d^2, a directional light
// of irradiance E gives E from -direction, at no distance's falloff.
LightSample sample_point_light(uint index, vec3 p, float pick) {
  PointLight l = point_lights[index];
  if (l.kind == kPunctualDirectional) return LightSample(-vec3(l.direction), kInfinity, vec3(l.intensity) / pick, 0.0f);
  vec3 d = vec3(l.position) - p;
  float dist2 = dot(d, d);
  float dist = sqrt(dist2);
  if (!(dist > 0.0f)) return no_light();
  vec3 wi = d / dist;
  float falloff = l.kind == kPunctualSpot ? spot_falloff(l, -dot(wi, vec3(l.direction))) : 1.0f;
  if (!(falloff > 0.0f)) return no_light();
  return LightSample(wi, dist, vec3(l.intensity) * (falloff / (dist2 * pick)), 0.0f);
}

#endif  // PT_PUNCTUAL_LIGHT_GLSL
