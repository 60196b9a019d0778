// The CPU backend's copy of stage3's kernel: the same integrator.glsl, compiled as C++
// inside its own namespace (docs/README.md, "One integrator source, two backends").
#include "common/backend.h"
#include "common/shaders/cpp_prelude.h"
#include "stage3_importance/kernels.h"

namespace stage3 {
using namespace pt::glsl;
#include "stage3_importance/integrator.glsl"
#include "common/shaders/cpu_kernel_impl.h"
}  // namespace stage3

#include "stage3_importance_spirv.h"  // generated: stage3_importance_spirv[]

pt::StageKernels stage3::kernels() {
  return pt::StageKernels{"stage3_importance", cpu_kernel(), stage3_importance_spirv};
}
