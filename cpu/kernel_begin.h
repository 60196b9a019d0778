// The start of a C++ kernel, included INSIDE the kernel's own namespace (after
// cpu/kernel_prelude.h at file level): the GLSL names of the subset and the scene arrays as
// globals. Then come the integrator and kernel_end.h. The build writes the stages' kernels
// this way (cmake/PtStage.cmake); tests compile variants of them the same way.
using namespace pt::glsl;
#include "cpu/kernel_bindings.h"
