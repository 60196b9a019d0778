// The CPU backend: a stage's kernel compiled as C++, run on all cores (cpu_backend.cpp).
#pragma once

#include <memory>

#include "common/render/backend.h"

namespace pt {

// threads: 0 = all cores.
std::unique_ptr<Backend> make_cpu_backend(const StageKernels& kernels, unsigned threads = 0);

}  // namespace pt
