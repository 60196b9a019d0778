// The grader's traps for lab PT_LAB's functions (cmake/Labs.cmake, PT_LAB_GRADED_STAGES;
// tools/grade_lab.py): the CPU kernel of a stage that none of the lab's tests runs is built
// once, at the grader's set-up, with these in place of the student's functions, so that a
// submission rebuilds only the kernels its tests run. Each says which function ran where
// and aborts (labs/lab_hooks.h): a test that runs a stage without its tag fails loudly
// instead of grading the reference. C++ only; included inside a kernel's namespace like the
// definitions it replaces. PT_LAB_UNGRADED_KERNEL is the stage (cmake/PtStage.cmake).
#include "common/kernel/lights.glsl"  // the types of the signatures below
#include "common/kernel/roulette.glsl"

#define PT_UNGRADED(function) pt::lab::ungraded(PT_LAB, #function, PT_LAB_UNGRADED_KERNEL)

#if PT_LAB == 2
vec3 sample_uniform_hemisphere(vec2) { PT_UNGRADED(sample_uniform_hemisphere); }
float uniform_hemisphere_pdf() { PT_UNGRADED(uniform_hemisphere_pdf); }
vec3 uniform_bounce_weight(vec3, vec3) { PT_UNGRADED(uniform_bounce_weight); }
float russian_roulette(vec3, uint) { PT_UNGRADED(russian_roulette); }
#elif PT_LAB == 3
vec3 sample_cosine_hemisphere(vec2) { PT_UNGRADED(sample_cosine_hemisphere); }
float cosine_hemisphere_pdf(float) { PT_UNGRADED(cosine_hemisphere_pdf); }
#elif PT_LAB == 4
LightSample sample_triangle_light(uint, vec3, vec2, float) { PT_UNGRADED(sample_triangle_light); }
float triangle_light_pdf(uint, vec3, float) { PT_UNGRADED(triangle_light_pdf); }
bool counts_emission(uint, bool) { PT_UNGRADED(counts_emission); }
#elif PT_LAB == 5
vec3 inverse_direction(vec3) { PT_UNGRADED(inverse_direction); }
vec2 box_span(Ray, vec3, vec3, vec3, float) { PT_UNGRADED(box_span); }
#elif PT_LAB == 6
float power_heuristic(float, float) { PT_UNGRADED(power_heuristic); }
float triangle_light_pdf_by_solid_angle(uint, vec3, vec3, float) { PT_UNGRADED(triangle_light_pdf_by_solid_angle); }
#endif

#undef PT_UNGRADED
