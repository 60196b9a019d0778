// stage2_montecarlo's kernel in both forms (C++ for the CPU, SPIR-V for Vulkan).
#pragma once

#include "common/render/backend.h"

namespace stage2 {
pt::StageKernels kernels();
}
