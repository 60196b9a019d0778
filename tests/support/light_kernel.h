// The kernel code of the light-sampling tests (stage4's light sample and shadow rays:
// tests/common/kernel/test_light_sampling.cpp, test_light_pick.cpp, test_shadow_rays.cpp;
// stage5_mis's: test_spherical_triangle.cpp, test_spherical_triangle_sampling.cpp,
// test_light_pdf.cpp, test_power_heuristic.cpp, test_light_pdf_integral.cpp), compiled as the CPU kernels
// compile it (the GPU compiles the same source): lights.glsl and what it needs, mis.glsl
// through kernel_support.h (kernel_definitions.glsl), and bind_scene. Include it inside the
// test file's own kernel namespace, itself in an anonymous namespace; no include guard,
// since each test file's namespace gets its own copy.
#include "cpu/kernel_begin.h"
#include "common/kernel/rng.glsl"
#include "common/kernel/camera.glsl"
#include "common/kernel/intersect.glsl"
#include "common/kernel/sampling.glsl"
#include "common/kernel/bsdf.glsl"
#include "common/kernel/spawn.glsl"
#include "common/kernel/lights.glsl"
#include "cpu/kernel_support.h"  // and through it mis.glsl (kernel_definitions.glsl)
#include "tests/support/kernel_scene_binding.h"
