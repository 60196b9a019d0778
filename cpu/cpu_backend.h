// The CPU backend: a stage's kernel compiled as C++, run on all cores (cpu_backend.cpp).
#pragma once

#include <memory>

#include "common/render/backend.h"
#include "cpu/kernel_scene.h"

namespace pt {

// threads: 0 = all cores.
std::unique_ptr<Backend> make_cpu_backend(const StageKernels& kernels, unsigned threads = 0);

struct WideBvh;
// Hands a CPU backend the wide tree of `bvh` made beforehand (build_wide_bvh(*bvh, the scene's
// triangles), cpu/wide_bvh.h): its set_scene, handed that same `bvh`, then takes `wide`
// instead of collapsing the tree again. For a caller that counts the CPU's tree as part of the
// BVH's build and renders one scene many times (pt_bench's stage section, issue 50); both must
// outlive the renders. nullptr forgets it; a backend that is not the CPU's ignores it.
void give_cpu_wide_bvh(Backend& backend, const Bvh* bvh, const WideBvh* wide);

}  // namespace pt
