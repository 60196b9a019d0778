// The lab check build's definitions of the functions labs 2-6 ask for (cmake/Labs.cmake,
// PT_LAB_CHECK): each calls the student's version from labs/labN.glsl when PT_LAB_STUB=N
// selects lab N at run time, else the reference, so one build shows every lab's tests
// failing with its stubs (tools/expect_lab_failure.sh). C++ only; included inside a kernel's
// namespace like the definitions it replaces.
#include "common/kernel/lights.glsl"  // what both versions use, outside the namespaces below

namespace reference {
#include "common/kernel/uniform_hemisphere.glsl"
#include "common/kernel/cosine_hemisphere.glsl"
#include "common/kernel/triangle_light.glsl"
#include "common/kernel/box_slab.glsl"
#include "common/kernel/mis.glsl"
}  // namespace reference

namespace student {
#include "labs/lab2.glsl"
#include "labs/lab3.glsl"
#include "labs/lab4.glsl"
#include "labs/lab5.glsl"
#include "labs/lab6.glsl"
}  // namespace student

vec3 sample_uniform_hemisphere(vec2 u) {
  return pt::lab::selected() == 2 ? student::sample_uniform_hemisphere(u) : reference::sample_uniform_hemisphere(u);
}
float uniform_hemisphere_pdf() {
  return pt::lab::selected() == 2 ? student::uniform_hemisphere_pdf() : reference::uniform_hemisphere_pdf();
}
vec3 sample_cosine_hemisphere(vec2 u) {
  return pt::lab::selected() == 3 ? student::sample_cosine_hemisphere(u) : reference::sample_cosine_hemisphere(u);
}
float cosine_hemisphere_pdf(float cos_theta) {
  return pt::lab::selected() == 3 ? student::cosine_hemisphere_pdf(cos_theta)
                                  : reference::cosine_hemisphere_pdf(cos_theta);
}
LightSample sample_triangle_light(uint index, vec3 p, vec2 u, float pick) {
  return pt::lab::selected() == 4 ? student::sample_triangle_light(index, p, u, pick)
                                  : reference::sample_triangle_light(index, p, u, pick);
}
float triangle_light_pdf(uint index, vec3 wi, float dist) {
  return pt::lab::selected() == 4 ? student::triangle_light_pdf(index, wi, dist)
                                  : reference::triangle_light_pdf(index, wi, dist);
}
vec3 inverse_direction(vec3 dir) {
  return pt::lab::selected() == 5 ? student::inverse_direction(dir) : reference::inverse_direction(dir);
}
vec2 box_span(Ray ray, vec3 inv_dir, vec3 lo, vec3 hi, float t_max) {
  return pt::lab::selected() == 5 ? student::box_span(ray, inv_dir, lo, hi, t_max)
                                  : reference::box_span(ray, inv_dir, lo, hi, t_max);
}
float power_heuristic(float mine, float other) {
  return pt::lab::selected() == 6 ? student::power_heuristic(mine, other) : reference::power_heuristic(mine, other);
}
float triangle_light_pdf_by_solid_angle(uint index, vec3 p, vec3 wi, float dist) {
  return pt::lab::selected() == 6 ? student::triangle_light_pdf_by_solid_angle(index, p, wi, dist)
                                  : reference::triangle_light_pdf_by_solid_angle(index, p, wi, dist);
}
