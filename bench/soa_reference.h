// pt_bench's speed section (issue 6, "Speed targets"): the machine's own reference for
// brute-force closest-hit ray casting, a plain C++ loop over a structure-of-arrays triangle
// list (Moller-Trumbore with precomputed edges) that the compiler vectorises.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace pt::bench {

struct SoaTriangles {
  std::vector<float> v0x, v0y, v0z, e1x, e1y, e1z, e2x, e2y, e2z;  // vertex 0 and two edges
  void add(glm::vec3 p0, glm::vec3 p1, glm::vec3 p2);
  std::size_t size() const { return v0x.size(); }
};

// Closest hit of each ray (origins o, unit directions d); returns the sum of the hit
// distances (so that the work cannot be optimised away). `avx2`: the loop compiled for
// AVX2's 8 lanes (where the CPU has it; else the same as false), not the compiler's
// default x86-64 target (SSE2, 4 lanes), which is what the project's own code is built for.
double soa_closest_hits(const SoaTriangles& tris, const glm::vec3* o, const glm::vec3* d, std::size_t count,
                        bool avx2 = false);

}  // namespace pt::bench
