// The CPU backend's copy of stage4's kernel: the same integrator.glsl, compiled as C++
// inside its own namespace (docs/README.md, "One integrator source, two backends").
#include "common/backend.h"
#include "common/shaders/cpp_prelude.h"
#include "stage4_direct_indirect/kernels.h"

namespace stage4 {
using namespace pt::glsl;
#include "stage4_direct_indirect/integrator.glsl"
#include "common/shaders/cpu_kernel_impl.h"
}  // namespace stage4

#include "stage4_direct_indirect_spirv.h"  // generated: stage4_direct_indirect_spirv[]

pt::StageKernels stage4::kernels() {
  return pt::StageKernels{"stage4_direct_indirect", cpu_kernel(), stage4_direct_indirect_spirv};
}
