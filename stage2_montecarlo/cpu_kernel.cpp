// The CPU backend's copy of stage2's kernel: the same integrator.glsl, compiled as C++
// inside its own namespace (docs/README.md, "One integrator source, two backends").
#include "common/backend.h"
#include "common/shaders/cpp_prelude.h"
#include "stage2_montecarlo/kernels.h"

namespace stage2 {
using namespace pt::glsl;
#include "stage2_montecarlo/integrator.glsl"
#include "common/shaders/cpu_kernel_impl.h"
}  // namespace stage2

#include "stage2_montecarlo_spirv.h"  // generated: stage2_montecarlo_spirv[]

pt::StageKernels stage2::kernels() {
  return pt::StageKernels{"stage2_montecarlo", cpu_kernel(), stage2_montecarlo_spirv};
}
