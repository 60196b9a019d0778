// The C++ half of the GLSL/C++ subset in which the integrators are written (docs/README.md,
// "One integrator source, two backends"). A C++ kernel includes this, opens its own
// namespace, and there includes kernel_begin.h, its integrator.glsl and kernel_end.h.
//
// Rules of the subset, kept by every file under common/kernel and stage*/integrator.glsl:
//   free functions and plain structs only; no references, pointers or recursion (paths are
//   loops with a throughput); float literals with an f suffix; no swizzles (single members
//   .x .y .z .w only); structs built as Type(a, b, c); per-invocation state (rng_state) is
//   a global, thread_local here; scene arrays are globals: SSBOs in GLSL, pointers here.
//   A vec3 field of the scene arrays that is an operand of arithmetic is read as
//   vec3(field): the arrays stay float where a test builds a kernel in double
//   (tests/stability/test_float_double.cpp), and the constructor converts it there.
#pragma once

#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>       // and <type_traits>: triangle_lanes.h, #included inside a namespace
#include <type_traits>

#include <glm/glm.hpp>

#include "common/kernel/scene_types.h"
#include "cpu/wide_bvh.h"  // the CPU's wide BVH, a kernel global (kernel_bindings.h)

namespace pt::glsl {
using namespace glm;
using namespace pt;  // the layouts and constants of scene_types.h
using uint = std::uint32_t;

// GLSL's abs() of floats: the sign bit cleared, as SPIR-V's FAbs does (abs(-0.0) is +0.0).
// glm's abs is x >= 0 ? x : -x, which keeps -0.0 and which GCC compiles to a branch on the
// sign: a ray's direction has random signs, so make_ray_shear() mispredicted about twice per
// ray. std::abs for scalars (<cmath> also puts it in the global namespace), these overloads
// for vectors; both are found before glm's templates.
using std::abs;
inline vec2 abs(vec2 v) {
  return vec2(std::fabs(v.x), std::fabs(v.y));
}
inline vec3 abs(vec3 v) {
  return vec3(std::fabs(v.x), std::fabs(v.y), std::fabs(v.z));
}
inline vec4 abs(vec4 v) {
  return vec4(std::fabs(v.x), std::fabs(v.y), std::fabs(v.z), std::fabs(v.w));
}

// GLSL's bitfieldReverse of a 32-bit word (bit 0 becomes bit 31): the Sobol sampler's
// mirroring (common/kernel/sampler.glsl). A byte swap, then three swaps inside each byte.
inline uint bitfieldReverse(uint x) {
  x = __builtin_bswap32(x);
  x = ((x & 0x0f0f0f0fu) << 4) | ((x >> 4) & 0x0f0f0f0fu);
  x = ((x & 0x33333333u) << 2) | ((x >> 2) & 0x33333333u);
  return ((x & 0x55555555u) << 1) | ((x >> 1) & 0x55555555u);
}

// GLSL's atomic built-ins on buffer memory (the kernel's event counters).
inline uint atomicAdd(uint& mem, uint data) {
  return std::atomic_ref<uint>(mem).fetch_add(data);
}
inline uint atomicMin(uint& mem, uint data) {
  std::atomic_ref<uint> a(mem);
  uint old = a.load();
  while (data < old && !a.compare_exchange_weak(old, data)) {
  }
  return old;
}
}  // namespace pt::glsl
