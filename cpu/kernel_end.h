// The end of a C++ kernel, included INSIDE its namespace after the integrator (which
// defines Li): the declared functions' definitions, the pixel loop and the CPU entry point
// (cpu_kernel(), which the backend calls).
#include "cpu/kernel_support.h"
#include "common/kernel/render_pixel.glsl"
#include "cpu/kernel_entry.h"
