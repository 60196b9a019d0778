// The lab check build's definitions of the functions labs 2-6 ask for (cmake/Labs.cmake,
// PT_LAB_CHECK): each calls the student's version from labs/labN.glsl when PT_LAB_STUB=N
// selects lab N at run time, a known-wrong answer when PT_LAB_MUTANT names one, else the
// reference, so one build shows every lab's tests failing with its stubs and with each of
// its mutants (tools/expect_lab_failure.sh). C++ only; included inside a kernel's
// namespace like the definitions it replaces.
#include "common/kernel/lights.glsl"  // what both versions use, outside the namespaces below
#include "common/kernel/roulette.glsl"

namespace reference {
#include "common/kernel/uniform_hemisphere.glsl"
#include "common/kernel/russian_roulette.glsl"
#include "common/kernel/cosine_hemisphere.glsl"
#include "common/kernel/triangle_light.glsl"
#include "common/kernel/emission_rule.glsl"
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

// PT_LAB_MUTANT=NAME at run time: the known-wrong answer NAME (labs/mutants.h) in place of
// the reference, so that CI sees each one fail its lab's tests. The labs' handouts hold no
// mutants (tools/make_lab_handout.py): there the hook does nothing.
#include "labs/mutants.h"
#ifdef PT_LAB_MUTANTS
#define PT_MUTANT(function, args)   \
  {                                 \
    auto m = mutant_##function args; \
    if (m.on) return m.value;       \
  }
#else
#define PT_MUTANT(function, args)
#endif

vec3 sample_uniform_hemisphere(vec2 u) {
  PT_MUTANT(sample_uniform_hemisphere, (u));
  return pt::lab::selected() == 2 ? student::sample_uniform_hemisphere(u) : reference::sample_uniform_hemisphere(u);
}
float uniform_hemisphere_pdf() {
  PT_MUTANT(uniform_hemisphere_pdf, ());
  return pt::lab::selected() == 2 ? student::uniform_hemisphere_pdf() : reference::uniform_hemisphere_pdf();
}
vec3 sample_cosine_hemisphere(vec2 u) {
  PT_MUTANT(sample_cosine_hemisphere, (u));
  return pt::lab::selected() == 3 ? student::sample_cosine_hemisphere(u) : reference::sample_cosine_hemisphere(u);
}
float cosine_hemisphere_pdf(float cos_theta) {
  PT_MUTANT(cosine_hemisphere_pdf, (cos_theta));
  return pt::lab::selected() == 3 ? student::cosine_hemisphere_pdf(cos_theta)
                                  : reference::cosine_hemisphere_pdf(cos_theta);
}
LightSample sample_triangle_light(uint index, vec3 p, vec2 u, float pick) {
  PT_MUTANT(sample_triangle_light, (index, p, u, pick));
  return pt::lab::selected() == 4 ? student::sample_triangle_light(index, p, u, pick)
                                  : reference::sample_triangle_light(index, p, u, pick);
}
float triangle_light_pdf(uint index, vec3 wi, float dist) {
  PT_MUTANT(triangle_light_pdf, (index, wi, dist));
  return pt::lab::selected() == 4 ? student::triangle_light_pdf(index, wi, dist)
                                  : reference::triangle_light_pdf(index, wi, dist);
}
vec3 inverse_direction(vec3 dir) {
  return pt::lab::selected() == 5 ? student::inverse_direction(dir) : reference::inverse_direction(dir);
}
vec2 box_span(Ray ray, vec3 inv_dir, vec3 lo, vec3 hi, float t_max) {
  PT_MUTANT(box_span, (ray, inv_dir, lo, hi, t_max));
  return pt::lab::selected() == 5 ? student::box_span(ray, inv_dir, lo, hi, t_max)
                                  : reference::box_span(ray, inv_dir, lo, hi, t_max);
}
float power_heuristic(float mine, float other) {
  PT_MUTANT(power_heuristic, (mine, other));
  return pt::lab::selected() == 6 ? student::power_heuristic(mine, other) : reference::power_heuristic(mine, other);
}
float triangle_light_pdf_by_solid_angle(uint index, vec3 p, vec3 wi, float dist) {
  PT_MUTANT(triangle_light_pdf_by_solid_angle, (index, p, wi, dist));
  return pt::lab::selected() == 6 ? student::triangle_light_pdf_by_solid_angle(index, p, wi, dist)
                                  : reference::triangle_light_pdf_by_solid_angle(index, p, wi, dist);
}
vec3 uniform_bounce_weight(vec3 f, vec3 wi) {
  PT_MUTANT(uniform_bounce_weight, (f, wi));
  return pt::lab::selected() == 2 ? student::uniform_bounce_weight(f, wi) : reference::uniform_bounce_weight(f, wi);
}
float russian_roulette(vec3 beta, uint mode) {
  PT_MUTANT(russian_roulette, (beta, mode));
  return pt::lab::selected() == 2 ? student::russian_roulette(beta, mode) : reference::russian_roulette(beta, mode);
}
bool counts_emission(uint depth, bool after_delta) {
  PT_MUTANT(counts_emission, (depth, after_delta));
  return pt::lab::selected() == 4 ? student::counts_emission(depth, after_delta)
                                  : reference::counts_emission(depth, after_delta);
}
