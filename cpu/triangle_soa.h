// The scene's triangles as a structure of arrays, for the CPU kernels' block test of the
// brute-force nearest-hit search (cpu/triangle_lanes.h; the article's raycasting
// step, Eq. 2). Nine arrays, one per vertex and axis (p0.x, p0.y, p0.z, p1.x, ...), each
// padded with empty triangles to a multiple of the block size so that a block never reads
// past the end; an empty triangle (all zeros) is rejected by its zero determinant.
#pragma once

#include <span>
#include <vector>

#include "common/kernel/scene_types.h"

namespace pt {

struct TriangleSoa {
  std::vector<float> data;  // 9 arrays of `stride` floats
  uint stride = 0;          // the padded triangle count

  explicit TriangleSoa(std::span<const Triangle> triangles, uint block = 8);
};

}  // namespace pt
