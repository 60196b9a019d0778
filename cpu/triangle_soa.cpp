// The scene's triangles as a structure of arrays (triangle_soa.h): the CPU kernels' layout
// for the block test of the nearest-hit search (Eq. 2's raycasting).
#include "cpu/triangle_soa.h"

namespace pt {

TriangleSoa::TriangleSoa(std::span<const Triangle> triangles, uint block) {
  stride = uint((triangles.size() + block - 1) / block * block);
  data.assign(std::size_t(stride) * 9, 0.0f);
  for (std::size_t i = 0; i < triangles.size(); i++) {
    const glm::vec3* vertices[3] = {&triangles[i].p0, &triangles[i].p1, &triangles[i].p2};
    for (int v = 0; v < 3; v++) {
      for (int k = 0; k < 3; k++) data[std::size_t(3 * v + k) * stride + i] = (*vertices[v])[k];
    }
  }
}

}  // namespace pt
