// Light sampling for stage4 (Eq. 5, corrected by erratum 5): pick a light in proportion
// to its power (the table built at load), then a point on it: uniform on a triangle's
// area (lab 4's sampler and pdf, in triangle_light.glsl), a direction in the cone a sphere
// subtends (sphere_light.glsl), the position of a point light (a delta), or a
// cosine-weighted direction of the uniform sky. Each sample carries Le / (pdf in solid
// angle x probability of the pick): the geometry term cos_y / d^2 and the area pdf 1 / A
// that the printed Eq. (5) lacks are in that pdf.
// stage5_mis (beyond the article) samples triangles by the solid angle they subtend
// instead, and needs each strategy's pdf for any direction (light_pdf, at the end; its
// triangles' part, triangle_light_pdf_by_solid_angle, is lab 6's and defined in mis.glsl).
#ifndef PT_LIGHTS_GLSL
#define PT_LIGHTS_GLSL

#include "common/kernel/sampling.glsl"
#include "common/kernel/intersect.glsl"
#include "common/kernel/spawn.glsl"
#include "common/kernel/spherical_triangle.glsl"
#include "common/kernel/texture.glsl"
#include "common/kernel/light_sample.glsl"
#include "common/kernel/punctual_light.glsl"
#include "common/kernel/environment.glsl"
#include "common/kernel/sphere_light.glsl"

// A point uniform on the area of the emissive triangle `index`, seen from p: defined in
// triangle_light.glsl, or by labs/lab4.glsl in lab 4's build (cmake/Labs.cmake).
LightSample sample_triangle_light(uint index, vec3 p, vec2 u, float pick);

// Stage4's emission rule (erratum 6): whether a hit's Le, or the sky, enters the sum after
// `depth` bounces, the last a delta (mirror, glass) or not. Defined in emission_rule.glsl,
// or by labs/lab4.glsl in lab 4's build.
bool counts_emission(uint depth, bool after_delta);

// The sky as a light. An environment map: a direction drawn from its distribution
// (environment.glsl), whatever n. The uniform sky: a cosine-weighted direction about the
// normal n, density cos / pi; for n = 0 (a lobe that transmits, bsdf.glsl
// light_sample_normal) uniform over the whole sphere, density 1 / (4 pi).
LightSample sample_sky(vec3 n, vec2 u, float pick) {
  if (has_environment()) {
    EnvironmentSample e = sample_environment(u);
    float pdf = e.pdf * pick;
    if (!(pdf > 0.0f)) return no_light();
    return LightSample(e.wi, kInfinity, e.radiance / pdf, pdf);
  }
  if (has_feature(kFeatureRoughGlass) && n.x == 0.0f && n.y == 0.0f && n.z == 0.0f) {
    float z = 1.0f - 2.0f * u.x;
    float r = sqrt(max(0.0f, 1.0f - z * z));
    float phi = 2.0f * kPi * u.y;
    float sphere_pdf = pick / (4.0f * kPi);
    if (!(sphere_pdf > 0.0f)) return no_light();
    return LightSample(vec3(r * cos(phi), r * sin(phi), z), kInfinity, vec3(params.sky) / sphere_pdf, sphere_pdf);
  }
  vec3 local = sample_cosine_hemisphere(u);
  float pdf = cosine_hemisphere_pdf(local.z) * pick;
  if (!(pdf > 0.0f)) return no_light();
  return LightSample(frame_to_world(make_frame(n), local), kInfinity, vec3(params.sky) / pdf, pdf);
}

// u rescaled from [lo, lo + width) to [0, 1): what is left of a number after it chose
// among intervals, so that one 2-D sample both picks and places (below).
float remap_within(float u, float lo, float width) {
  return min((u - lo) / width, kOneMinusEpsilon);
}

// The light a number u in [0, 1) picks, and what is left of u for placing the point.
struct LightPick {
  uint entry;   // the light table's entry
  Light light;  // lights[entry]
  float u;      // uniform in [0, 1) again, whichever light u picked
};

// Walker's alias method (the light table's alias table, scene.h light_alias): u x
// light_count chooses a cell, all cells equally likely, and the fraction of u within the
// cell picks the cell's own light below its threshold, its alias above. Both entries are
// copied into the cell, so a pick reads one 32-byte record, however many lights there are:
// one cache miss among a million emitting triangles, where a search of the cumulative
// probabilities read a guide and then the table. That fraction, rescaled to the part of the
// cell that picked, is the number left for the light's own sample.
LightPick pick_light_entry(float u) {
  float scaled = u * float(params.light_count);
  uint cell = min(uint(scaled), params.light_count - 1u);
  prefetch_light_triangle(cell);  // the CPU asks for the likely triangle meanwhile (a hint)
  LightAlias a = light_alias_at(cell);
  float f = min(scaled - float(cell), kOneMinusEpsilon);
  if (f < a.threshold) return LightPick(cell, a.own, remap_within(f, 0.0f, a.threshold));
  return LightPick(a.alias, a.other, remap_within(f, a.threshold, 1.0f - a.threshold));
}

// The probability that sample_light chooses the sky, and that it chooses entry `light` of
// the light table.
float sky_pick_probability() {
  return has_feature(kFeatureSky) ? params.sky_pick : 0.0f;
}

float light_pick_probability(uint light) {
  return (1.0f - sky_pick_probability()) * lights[light].pick;
}

// How a light sample places its point on a triangle: uniform on its area (stage4, the
// article's way), or uniform in the solid angle it subtends (stage5_mis).
const uint kTriangleByArea = 0u;
const uint kTriangleBySolidAngle = 1u;

// Whether the triangle faces p: a one-sided emitter lights only the side its front faces.
bool triangle_lights_point(Triangle tri, vec3 p) {
  if (materials[tri.material].double_sided != 0u) return true;
  vec3 c = cross(vec3(tri.p1 - tri.p0), vec3(tri.p2 - tri.p0));
  return dot(p - vec3(tri.p0), c) > 0.0f;
}

// Whether the light sample of a triangle seen as t is drawn by solid angle: within
// kMinSphericalTriangle..kMaxSphericalTriangle (spherical_triangle.glsl); else by area.
// The sampler and light_pdf both decide by this one function, so their pdfs agree.
bool sample_by_solid_angle(SphericalTriangle t) {
  return t.area >= kMinSphericalTriangle && t.area <= kMaxSphericalTriangle;
}

// A direction uniform in the solid angle of the emissive triangle `index` seen from p:
// density pick / solid angle, constant over the triangle (stage5_mis).
LightSample sample_triangle_light_by_solid_angle(uint index, vec3 p, vec2 u, float pick) {
  Triangle tri = triangles[index];
  if (!triangle_lights_point(tri, p)) return no_light();
  SphericalTriangle t = spherical_triangle(p, vec3(tri.p0), vec3(tri.p1), vec3(tri.p2));
  if (!sample_by_solid_angle(t)) return sample_triangle_light(index, p, u, pick);
  vec3 wi = spherical_triangle_sample(t, u);
  // The distance to the triangle's plane along wi.
  vec3 normal = cross(vec3(tri.p1 - tri.p0), vec3(tri.p2 - tri.p0));
  float dist = dot(vec3(tri.p0) - p, normal) / dot(wi, normal);
  if (!(dist > 0.0f) || isinf(dist)) return no_light();
  float pdf = pick / t.area;
  return LightSample(wi, dist, triangle_emission_at(index, p + dist * wi) / pdf, pdf);
}

// A light sample on a triangle with an alpha mask (alphaMode MASK) that lands in one of
// its holes finds no emitter there (intersect.glsl cut_out): no light, while the pdf of
// every other point stays that of the whole triangle, as the BSDF's rays that meet the
// triangle outside its holes are weighed (light_pdf). Unbiased: the holes emit nothing.
LightSample unless_in_hole(uint index, vec3 p, LightSample ls) {
  if (!has_feature(kFeatureAlphaMask) || (triangle_at(index).flags & kTriangleMasked) == 0u) return ls;
  if (!(ls.dist > 0.0f)) return ls;
  vec2 b = barycentric_at(index, p + ls.dist * ls.wi);
  if (cut_out(index, b.x, b.y)) return no_light();
  return ls;
}

// One light sample for the shading point p with normal n (on the side light may come from),
// its triangles placed by `triangles_by` (kTriangleByArea or kTriangleBySolidAngle).
// One 2-D sample does both steps: its first coordinate picks the light and, rescaled to
// the picked light's interval, places the point with the second coordinate. Two separate
// samples would be as unbiased, but a stratified sampler (sampler.glsl) would then
// stratify the pick and the point each on its own, not the points of each light.
LightSample sample_light_by(vec3 p, vec3 n, uint triangles_by) {
  vec2 u2 = sample_2d();
  float sky_pick = sky_pick_probability();
  if (u2.x < sky_pick) return sample_sky(n, vec2(remap_within(u2.x, 0.0f, sky_pick), u2.y), sky_pick);
  if (params.light_count == 0u) return no_light();
  float u = remap_within(u2.x, sky_pick, 1.0f - sky_pick);
  LightPick picked = pick_light_entry(u);
  Light light = picked.light;
  u2.x = picked.u;
  float pick = (1.0f - sky_pick) * light.pick;
  if (!has_feature(kFeatureSphereLights | kFeaturePointLights) || light.kind == kLightTriangle) {
    if (triangles_by == kTriangleBySolidAngle) {
      return unless_in_hole(light.index, p, sample_triangle_light_by_solid_angle(light.index, p, u2, pick));
    }
    return unless_in_hole(light.index, p, sample_triangle_light(light.index, p, u2, pick));
  }
  if (!has_feature(kFeaturePointLights) || light.kind == kLightSphere) {
    return sample_sphere_light(light.index, p, u2, pick);
  }
  return sample_point_light(light.index, p, pick);
}

// stage4's light sample: triangles by area, as the article's Eq. (5).
LightSample sample_light(vec3 p, vec3 n) {
  return sample_light_by(p, n, kTriangleByArea);
}

// The pdf (solid angle x pick) with which sample_light draws the direction wi that meets the
// triangle `index` at distance dist, by area (0 if no light or facing away): defined in
// triangle_light.glsl, or by labs/lab4.glsl in lab 4's build (cmake/Labs.cmake).
float triangle_light_pdf(uint index, vec3 wi, float dist);

// The pdf (solid angle x pick probability) with which sample_light_by(p, n,
// kTriangleBySolidAngle) draws the direction wi from p that meets the triangle `index` at
// distance dist; 0 where the triangle is no light or does not face p. light_pdf's answer
// for a triangle: defined in mis.glsl, or by labs/lab6.glsl in lab 6's build (cmake/Labs.cmake).
float triangle_light_pdf_by_solid_angle(uint index, vec3 p, vec3 wi, float dist);

// The pdf with which sample_light_by(p, n, kTriangleBySolidAngle) picks the direction wi
// from p, when wi meets the surface `hit` at distance dist (0 where that surface is no
// light): what stage5_mis weighs a BRDF sample's emission with.
float light_pdf(vec3 p, vec3 wi, Hit hit, float dist) {
  if (!has_feature(kFeatureSpheres) || hit.kind == kPrimTriangle) {
    return triangle_light_pdf_by_solid_angle(hit.prim, p, wi, dist);
  }
  Sphere s = spheres[hit.prim];
  if (s.light == kNoLight) return 0.0f;
  float pick = light_pick_probability(s.light);
  if (!inside_sphere_light(s, p)) {
    vec3 to_center = vec3(s.center) - p;
    return pick / (2.0f * kPi * sphere_cone_one_minus_cos(s.radius, dot(to_center, to_center)));
  }
  if (materials[s.material].double_sided == 0u) return 0.0f;
  vec3 n = (p + dist * wi - vec3(s.center)) / float(s.radius);
  float cos_y = abs(dot(wi, n));
  if (!(cos_y > 0.0f)) return 0.0f;
  return dist * dist / (cos_y * 4.0f * kPi * s.radius * s.radius) * pick;
}

// The pdf with which sample_light picks the sky in direction wi from a point whose normal
// (on the side light comes from) is n.
float sky_light_pdf(vec3 n, vec3 wi) {
  if (has_environment()) return sky_pick_probability() * environment_pdf(wi);
  if (has_feature(kFeatureRoughGlass) && n.x == 0.0f && n.y == 0.0f && n.z == 0.0f) {
    return sky_pick_probability() / (4.0f * kPi);  // the whole sphere (sample_sky)
  }
  return sky_pick_probability() * cosine_hemisphere_pdf(max(dot(n, wi), 0.0f));
}

// Units in the last place of the light point's coordinates that a shadow ray's last stretch
// spans at least: p + dist wi rebuilds the point only to within a few ulps of its magnitude,
// which far from the origin (ulp 0.0078 at 1e5) is far more than the relative 1e-4 of a
// short ray.
const float kShadowEndUlps = 16.0f;

// Whether a ray's hit is on a light (an emissive triangle or sphere of the light table).
bool hit_is_light(Hit hit) {
  if (!has_feature(kFeatureSpheres) || hit.kind == kPrimTriangle) return triangle_at(hit.prim).light != kNoLight;
  return spheres[hit.prim].light != kNoLight;
}

// Whether anything lies between the surface point p (normal n) and the light sample. The
// shadow ray starts off the surface (spawn_ray), and aims at the light point itself (pbrt's
// SpawnRayTo). The nearest surface it meets decides: before the last stretch (1e-4 of the
// ray's length, or kShadowEndUlps of the point) any surface blocks it; within the stretch
// the light's own surface may be met first, since neither the point nor its hit is exact
// (3e-5 of the length at a grazing angle to smallpt's light), so there a surface blocks
// only if it is no light. So a light poking through a wall (smallpt's, 0.27 through its
// ceiling) is hidden right above the wall, and not shadowed by itself
// (tests/common/kernel/test_shadow_rays.cpp). The nearest hit costs about what an any-hit
// search costs where most shadow rays are clear (stage4 on the Cornell box: 3% slower).
bool occluded(vec3 p, vec3 n, LightSample ls) {
  Ray shadow = spawn_ray(p, n, ls.wi);
  if (ls.dist == kInfinity) return occluded_scene(shadow, kInfinity);
  vec3 y = p + ls.dist * ls.wi;
  vec3 to_light = y - shadow.origin;
  float length_to_light = length(to_light);
  shadow.dir = to_light / length_to_light;
  float last = max(length_to_light * 1e-4f, kShadowEndUlps * ulp_above(max(abs(y.x), max(abs(y.y), abs(y.z)))));
  Hit hit = intersect_scene(shadow, length_to_light);
  return hit.kind != kPrimNone && (hit.t < length_to_light - last || !hit_is_light(hit));
}

#endif  // PT_LIGHTS_GLSL
