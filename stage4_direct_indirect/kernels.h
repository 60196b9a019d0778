// stage4_direct_indirect's kernel in both forms (C++ for the CPU, SPIR-V for Vulkan).
#pragma once

#include "common/render/backend.h"

namespace stage4 {
pt::StageKernels kernels();
}
