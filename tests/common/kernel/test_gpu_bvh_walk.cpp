// The GPU's tuned BVH walk (gpu/bvh_walk.glsl: packed stack, a loop per descent, the pop
// written twice) compiled here as C++, so that the same checks as the plain walk's
// (test_bvh_traversal.cpp) hold for it without a GPU: the brute force's hits bit for bit on
// random, tied and degenerate scenes, and its any-hit answers. The step after the article.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <random>

#include "common/scene/bvh.h"
#include "common/scene/scene.h"
#include "tests/support/random_scenes.h"
#include "cpu/kernel_prelude.h"

namespace {  // internal linkage: each test file compiles its own copy of the kernel code
namespace kernel {
#include "cpu/kernel_begin.h"
#include "common/kernel/camera.glsl"
#include "common/kernel/intersect.glsl"
#include "kernel_definitions.glsl"
#include "gpu/bvh_walk.glsl"  // instead of common/kernel/bvh.glsl (cpu/kernel_support.h)
#include "cpu/triangle_lanes.h"
#include "cpu/sphere_lanes.h"
}  // namespace kernel

#include "tests/support/bvh_walk_check.h"

}  // namespace

TEST_CASE("bvh: the GPU's tuned walk finds the brute force's hit bit for bit on random scenes", "[bvh]") {
  check_random_scenes();
}

TEST_CASE("bvh: the GPU's tuned walk gives ties between coplanar triangles to the lower index", "[bvh]") {
  check_coplanar_ties(coplanar_overlaps());
}

TEST_CASE("bvh: the GPU's tuned walk on degenerate scenes: one point, one triangle, none, copies, 1e-6 to 1e6",
          "[bvh]") {
  check_degenerate_scenes();
}
