// Lab 4 (docs/labs/lab4.md): light sampling, the article's Eq. (5) corrected (erratum 5):
// the direct light from an emissive triangle needs the geometry term cos_y / d^2 and the
// area pdf 1 / A that the printed formula lacks. Write the sample of one triangle light,
// the pdf of a direction that meets it, and the rule that keeps a light's emission from
// being counted twice (erratum 6). Built instead of common/kernel/triangle_light.glsl and
// emission_rule.glsl when you configure with -DPT_LAB=4. Graded by `ctest -L lab4`.
// Written in the GLSL/C++ subset (docs/README.md): it runs on both backends.

#include "labs/lab_support.glsl"
#include "common/kernel/lights.glsl"

// index: the triangle (triangles[index], corners p0 p1 p2, material materials[tri.material]);
// p: the shading point; u: two uniform numbers in [0, 1); pick: the probability with which
// this light was chosen. Draw a point y uniform on the triangle's area and return
//   LightSample(wi, dist, Le / pdf, pdf)
// where wi is the unit direction from p to y, dist = |y - p|, Le the material's emission,
// and pdf the density of wi in solid angle times pick: (1 / A) * d^2 / cos_y * pick, with
// cos_y the cosine at y between the triangle's normal and -wi. The triangle emits from its
// front face only (cross(p1 - p0, p2 - p0) points out of it) unless the material is
// double-sided (double_sided != 0u: use |cos_y|). Return no_light() when y does not face p.
LightSample sample_triangle_light(uint index, vec3 p, vec2 u, float pick) {
  // Your code here. Remove the line below when you are done.
  float nan = PT_LAB_NOT_WRITTEN(4, sample_triangle_light) * u.x * pick;
  return LightSample(p, nan, vec3(nan), float(index) * nan);
}

// index: a triangle that the ray from a point in the unit direction wi meets at distance
// dist. Return the pdf with which sample_triangle_light, with pick the probability
// of choosing this light (light_pick_probability(tri.light)), draws wi: the same number as
// the sample's pdf for that point. Return 0 when the triangle is no light
// (tri.light == kNoLight) or, one-sided, is seen from behind.
float triangle_light_pdf(uint index, vec3 wi, float dist) {
  // Your code here. Remove the line below when you are done.
  return PT_LAB_NOT_WRITTEN(4, triangle_light_pdf) * float(index) * dist * wi.x;
}

// Stage4 adds a light sample at every hit that is not a mirror or glass, and its bounce
// rays then go on as in stage3. Return whether the emission Le of the surface (or the sky)
// that a ray meets enters the sum: depth is 0 for the camera ray and k after k bounces,
// after_delta tells whether the last bounce was a mirror or glass (a delta lobe, where no
// light sample is taken). Count each light's contribution to a path once, not twice, and
// not zero times.
bool counts_emission(uint depth, bool after_delta) {
  // Your code here. Remove the line below when you are done.
  return PT_LAB_NOT_WRITTEN(4, counts_emission) == float(depth) && after_delta;
}
