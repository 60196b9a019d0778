// A kernel that is not a stage, for the sampler's tests (tests/gpu/test_sampler_agree.cpp):
// its "radiance" is the sampler's next numbers (common/kernel/sampler.glsl), dimension 1 (a
// sample_1d) and dimension 2 (a sample_2d), so a 1-spp image shows them exactly and the
// CPU's and the GPU's can be compared bit for bit. Built by tests/CMakeLists.txt with
// pt_add_stage(... INTEGRATOR ...).
#include "common/kernel/sampler.glsl"
#include "common/kernel/camera.glsl"
#include "common/kernel/intersect.glsl"

vec3 Li(Ray) {  // the camera ray is not needed: the probe returns its sampler's values
  float a = sample_1d();
  vec2 b = sample_2d();
  return vec3(a, b.x, b.y);
}
