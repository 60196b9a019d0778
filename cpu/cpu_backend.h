// The CPU backend: a stage's kernel compiled as C++, run on all cores (cpu_backend.cpp).
#pragma once

#include <cstdint>
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

// The stages whose CPU kernel ran a pass in this process since clear_cpu_stages_run(): bit
// K-1 for stageK (the number in StageKernels::name, "stage2_montecarlo"). The CPU test
// program checks with it that a test carries the tag of every stage it runs
// (tests/test_main.cpp): the stages' regression labels and the grader's choice of the
// kernels a submission rebuilds (labs/ungraded.h) rest on those tags.
std::uint32_t cpu_stages_run();
void clear_cpu_stages_run();

}  // namespace pt
