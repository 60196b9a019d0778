// stage3_importance's kernel in both forms (C++ for the CPU, SPIR-V for Vulkan).
#pragma once

#include "common/render/backend.h"

namespace stage3 {
pt::StageKernels kernels();
}
