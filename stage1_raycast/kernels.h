// stage1_raycast's kernel in both forms (C++ for the CPU, SPIR-V for Vulkan).
#pragma once

#include "common/render/backend.h"

namespace stage1 {
pt::StageKernels kernels();
}
