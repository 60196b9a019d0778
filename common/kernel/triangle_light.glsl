// Light sampling of one emissive triangle for stage4 (the article's Eq. 5, corrected by
// erratum 5), and the pdf of a direction that meets the triangle, both declared in
// lights.glsl. Lab 4 (docs/labs/lab4.md) asks the student for these two functions: its
// build compiles labs/lab4.glsl instead of this file.
#ifndef PT_TRIANGLE_LIGHT_GLSL
#define PT_TRIANGLE_LIGHT_GLSL

#include "common/kernel/lights.glsl"
#include "common/kernel/texture.glsl"

// A point uniform on the triangle: density 1 / area (Turk's square-root mapping).
LightSample sample_triangle_light(uint index, vec3 p, vec2 u, float pick) {
  Triangle tri = triangles[index];
  vec3 p0 = tri.p0;
  vec3 p1 = tri.p1;
  vec3 p2 = tri.p2;
  float su = sqrt(u.x);
  vec3 y = (1.0f - su) * p0 + su * (1.0f - u.y) * p1 + su * u.y * p2;
  vec3 c = cross(p1 - p0, p2 - p0);
  float area = 0.5f * length(c);
  vec3 n = normalize(c);
  vec3 d = y - p;
  float dist2 = dot(d, d);
  float dist = sqrt(dist2);
  vec3 wi = d / dist;
  Material m = materials[tri.material];
  float cos_y = dot(-wi, n);
  // Le from the front face only, unless double-sided (the contract (README.md)).
  if (m.double_sided != 0u) cos_y = abs(cos_y);
  if (!(cos_y > 0.0f) || !(dist > 0.0f)) return no_light();
  float pdf = dist2 / (cos_y * area) * pick;  // area pdf 1/A turned into solid angle
  // Le at y: the emission times the emissive texture there (texture.glsl), at y's
  // barycentric weights su (1 - u.y) of p1 and su u.y of p2.
  return LightSample(wi, dist, triangle_emission(index, su * (1.0f - u.y), su * u.y) / pdf, pdf);
}

// The same density for a direction wi from a point that meets the emissive triangle `index`
// at distance dist: d^2 / (cos_y area), times the probability of picking the light. What a
// light sample's pdf must equal (the tests check it), and light_pdf's answer where stage5
// samples a triangle by area too (mis.glsl).
float triangle_light_pdf(uint index, vec3 wi, float dist) {
  Triangle tri = triangles[index];
  if (tri.light == kNoLight) return 0.0f;
  vec3 c = cross(vec3(tri.p1 - tri.p0), vec3(tri.p2 - tri.p0));
  float area = 0.5f * length(c);
  float cos_y = dot(-wi, normalize(c));
  if (materials[tri.material].double_sided != 0u) cos_y = abs(cos_y);
  if (!(cos_y > 0.0f)) return 0.0f;
  return dist * dist / (cos_y * area) * light_pick_probability(tri.light);
}

#endif  // PT_TRIANGLE_LIGHT_GLSL
