// Lab 3 (docs/labs/lab3.md): importance sampling, the article's Eq. (4) corrected
// (erratum 2): directions drawn in proportion to cos(theta), weighted f cos / pdf. Write
// the cosine-weighted sampler and its pdf. Built instead of the real functions of
// common/kernel/cosine_hemisphere.glsl when you configure with -DPT_LAB=3. Graded by `ctest -L lab3`.
// Written in the GLSL/C++ subset (docs/README.md): it runs on both backends.

#include "labs/lab_support.glsl"
#include "common/kernel/sampling.glsl"

// u: two independent numbers uniform in [0, 1). Return a unit direction (x, y, z) with
// z >= 0, distributed with density cos(theta) / pi in solid angle (z = cos(theta)).
vec3 sample_cosine_hemisphere(vec2 u) {
  // Your code here. Remove the line below when you are done.
  return vec3(PT_LAB_NOT_WRITTEN(3, sample_cosine_hemisphere)) * u.x;
}

// The density of sample_cosine_hemisphere at a direction whose cosine to the normal
// is cos_theta; 0 below the surface (cos_theta <= 0).
float cosine_hemisphere_pdf(float cos_theta) {
  // Your code here. Remove the line below when you are done.
  return PT_LAB_NOT_WRITTEN(3, cosine_hemisphere_pdf) * cos_theta;
}
