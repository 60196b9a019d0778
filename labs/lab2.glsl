// Lab 2 (docs/labs/lab2.md): the Monte Carlo estimator of the article's Eq. (3) with its
// corrected factor 2 pi / N (erratum 1). Write the uniform hemisphere sampler and its pdf;
// stage2 divides f * Lin * cos by that pdf. Built instead of the real functions of
// common/kernel/uniform_hemisphere.glsl when you configure with -DPT_LAB=2. Graded by `ctest -L lab2`.
// Written in the GLSL/C++ subset (docs/README.md): it runs on both backends.

#include "labs/lab_support.glsl"
#include "common/kernel/sampling.glsl"

// u: two independent numbers uniform in [0, 1). Return a unit direction (x, y, z) with
// z > 0 (z is the cosine to the normal), uniform over the hemisphere: its density in solid
// angle must be the same everywhere.
vec3 sample_uniform_hemisphere(vec2 u) {
  // Your code here. Remove the line below when you are done.
  return vec3(PT_LAB_NOT_WRITTEN(2, sample_uniform_hemisphere)) * u.x;
}

// The density of sample_uniform_hemisphere in solid angle (per steradian).
float uniform_hemisphere_pdf() {
  // Your code here. Remove the line below when you are done.
  return PT_LAB_NOT_WRITTEN(2, uniform_hemisphere_pdf);
}
