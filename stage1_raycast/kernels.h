// stage1_raycast's kernel in both forms (C++ for the CPU, SPIR-V for Vulkan).
#pragma once

#include "common/backend.h"

namespace stage1 {
pt::StageKernels kernels();
}
