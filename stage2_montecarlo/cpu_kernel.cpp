// The CPU backend's copy of stage2's kernel: the same integrator.glsl, compiled as C++
// inside its own namespace (docs/README.md, "One integrator source, two backends"), once
// per feature variant (cpu/cpu_variants.h; the build makes the copies).
#include "common/render/backend.h"
#include "cpu/cpu_variants.h"
#include "cpu/kernel_prelude.h"

namespace stage2::PT_CPU_VARIANT_NS {
using namespace pt::glsl;
#include "stage2_montecarlo/integrator.glsl"
#include "cpu/kernel_entry.h"
}  // namespace stage2::PT_CPU_VARIANT_NS
