// The CPU backend's copy of stage1's kernel: the same integrator.glsl, compiled as C++
// inside its own namespace (docs/README.md, "One integrator source, two backends").
#include "common/backend.h"
#include "common/shaders/cpp_prelude.h"
#include "stage1_raycast/kernels.h"

namespace stage1 {
using namespace pt::glsl;
#include "stage1_raycast/integrator.glsl"
#include "common/shaders/cpu_kernel_impl.h"
}  // namespace stage1

#include "stage1_raycast_spirv.h"  // generated: stage1_raycast_spirv[]

pt::StageKernels stage1::kernels() {
  return pt::StageKernels{"stage1_raycast", cpu_kernel(), stage1_raycast_spirv};
}
