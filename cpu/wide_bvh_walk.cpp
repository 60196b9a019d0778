// The walk of the CPU's wide BVH (wide_bvh.h; the step after the article's GPU section,
// which ends "yet without an acceleration structure"): a node's 8 boxes by one slab test on
// SIMD lanes, box_span() of common/kernel/box_slab.glsl on each lane with the margin of the
// root's box, no smaller than any box's own (the same rounding up, so never a miss where the
// binary walk would not miss), the hit
// children near to far on a stack (skipped when popped beyond the best hit), and a leaf's
// triangles by hit_triangle_lanes() (triangle_lane_ops.h) with the brute force's tie rule.
// AVX-512, AVX2 (8 lanes) or 4 lanes, chosen at run time as triangle_lanes.h chooses: this
// file is compiled once per instruction set (wide_bvh_walk_avx2.cpp and _avx512.cpp include
// it with PT_WIDE_WALK_ISA 1 and 2), so that each copy turns its hit mask into bits with its
// own instruction; compiled by itself it is the 4-lane copy and the dispatch.
#include "cpu/wide_bvh.h"

#include <cmath>

#include "cpu/kernel_prelude.h"

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define PT_WIDE_DISPATCH 1
#include <immintrin.h>
#endif
#ifndef PT_WIDE_WALK_ISA
#define PT_WIDE_WALK_ISA 0
#endif
// Everything defined below, the kernel code included, is compiled for the copy's instruction
// set; the headers above (whose inline functions are shared with other files) are not.
#if PT_WIDE_DISPATCH && PT_WIDE_WALK_ISA == 1
#pragma GCC target("avx2")
#elif PT_WIDE_DISPATCH && PT_WIDE_WALK_ISA == 2
#pragma GCC target("avx2,avx512f,avx512vl")
#endif

// The kernel code below is there for a few of its functions; the rest goes unused here.
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wunused-variable"

namespace {
namespace kernel {  // hit_triangle()'s constants and types, the slab test's margins
#include "cpu/kernel_begin.h"
#include "common/kernel/box_pad.glsl"
#include "common/kernel/intersect.glsl"
#include "cpu/triangle_lane_ops.h"
}  // namespace kernel

using namespace kernel;

// Stack entries: at most 7 pending siblings per level of a tree shallower than the binary one.
constexpr int kWideStack = int(kBvhStackSize) * kWideWidth;

#include "cpu/wide_bvh_walk_lanes.h"  // Walk: a node's boxes and a leaf's triangles on lanes

template <int bytes>
[[gnu::always_inline]] inline pt::WideHit nearest(const pt::WideBvh& bvh, const pt::WideRay& ray, pt::WideHit in) {
  const Walk<bytes> walk(ray, root_pad(bvh, ray));
  Hit best(in.t, in.b1, in.b2, uint(in.prim), in.prim >= 0 ? kPrimTriangle : kPrimNone);
  std::int32_t stack_ref[kWideStack];
  float stack_t[kWideStack];
  int top = 0;
  std::int32_t ref = 0;
  while (true) {
    if (ref >= 0) {
      const pt::WideNode& n = bvh.nodes[std::size_t(ref)];
      float enter[pt::kWideWidth];
      unsigned bits = walk.children(n, best.t, enter);
      if (bits != 0u) {
        int i = __builtin_ctz(bits);
        bits &= bits - 1u;
        if (bits == 0u) {
          ref = n.child[i];
          continue;
        }
        // Two or more: all on the stack, nearest last (insertion by entry distance), and
        // the nearest taken straight off again.
        const int base = top;
        for (;; i = __builtin_ctz(bits), bits &= bits - 1u) {
          int j = top++;
          for (; j > base && stack_t[j - 1] < enter[i]; j--) stack_ref[j] = stack_ref[j - 1], stack_t[j] = stack_t[j - 1];
          stack_ref[j] = n.child[i], stack_t[j] = enter[i];
          if (bits == 0u) break;
        }
        ref = stack_ref[--top];
        continue;
      }
    } else {
      best = walk.template leaf<true>(bvh.blocks[std::size_t(~ref)], best);
      if (best.kind == kPrimTriangle && bvh.shading) {  // the triangle the kernel reads next (48 bytes)
        const char* tri = reinterpret_cast<const char*>(bvh.shading + best.prim);
        __builtin_prefetch(tri), __builtin_prefetch(tri + sizeof(pt::Triangle) - 1);
      }
    }
    // Nothing below: the next pending child that a hit could still lie in.
    while (top > 0 && !(stack_t[top - 1] <= best.t)) top--;
    if (top == 0) break;
    ref = stack_ref[--top];
  }
  if (best.kind != kPrimTriangle) return in;
  return pt::WideHit{best.t, best.b1, best.b2, std::int32_t(best.prim)};
}

template <int bytes>
[[gnu::always_inline]] inline bool occluded(const pt::WideBvh& bvh, const pt::WideRay& ray, float t_max) {
  const Walk<bytes> walk(ray, root_pad(bvh, ray));
  const Hit none(t_max, 0.0f, 0.0f, 0u, kPrimNone);
  std::int32_t stack_ref[kWideStack];
  int top = 0;
  stack_ref[top++] = 0;
  while (top > 0) {
    const std::int32_t ref = stack_ref[--top];
    if (ref >= 0) {
      const pt::WideNode& n = bvh.nodes[std::size_t(ref)];
      float enter[pt::kWideWidth];
      for (unsigned bits = walk.children(n, t_max, enter); bits != 0u; bits &= bits - 1u)
        stack_ref[top++] = n.child[__builtin_ctz(bits)];
    } else if (walk.template leaf<false>(bvh.blocks[std::size_t(~ref)], none).kind != kPrimNone) {
      return true;
    }
  }
  return false;
}

}  // namespace

// The copies per instruction set (PT_WIDE_WALK_ISA 1: AVX2, 2: AVX-512 on 8 lanes, its 32
// vector registers instead of 16), each defined by its own file, and the dispatch.
namespace pt::wide_walk {
WideHit nearest_avx2(const WideBvh& bvh, const WideRay& ray, WideHit best);
bool occluded_avx2(const WideBvh& bvh, const WideRay& ray, float t_max);
WideHit nearest_avx512(const WideBvh& bvh, const WideRay& ray, WideHit best);
bool occluded_avx512(const WideBvh& bvh, const WideRay& ray, float t_max);
#if PT_WIDE_DISPATCH && PT_WIDE_WALK_ISA == 1
WideHit nearest_avx2(const WideBvh& bvh, const WideRay& ray, WideHit best) { return nearest<32>(bvh, ray, best); }
bool occluded_avx2(const WideBvh& bvh, const WideRay& ray, float t_max) { return occluded<32>(bvh, ray, t_max); }
#elif PT_WIDE_DISPATCH && PT_WIDE_WALK_ISA == 2
WideHit nearest_avx512(const WideBvh& bvh, const WideRay& ray, WideHit best) { return nearest<32>(bvh, ray, best); }
bool occluded_avx512(const WideBvh& bvh, const WideRay& ray, float t_max) { return occluded<32>(bvh, ray, t_max); }
#endif
}  // namespace pt::wide_walk

#if PT_WIDE_WALK_ISA == 0
namespace {
#if PT_WIDE_DISPATCH
// 2: AVX-512, 1: AVX2, 0: 4 lanes, asked of the CPU once, when the program starts (a
// constructor like this one may run before libgcc's own: hence __builtin_cpu_init).
const int kBestLevel = [] {
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx512vl") ? 2 : __builtin_cpu_supports("avx2") ? 1 : 0;
}();
// The copy to run: `lanes` 4 asks for 4 lanes, 8 for at least AVX2, 0 for the best.
inline int level(int lanes) {
  return lanes == 4 ? 0 : lanes == 8 ? (kBestLevel > 0 ? 1 : 0) : kBestLevel;
}
#endif
// The 4-lane copies as functions of their own: inlined into the dispatch below, their stack
// frame (the walk's stack) was set up on every call, whichever copy ran (issue 50).
[[gnu::noinline]] pt::WideHit nearest_4(const pt::WideBvh& bvh, const pt::WideRay& ray, pt::WideHit best) {
  return nearest<16>(bvh, ray, best);
}
[[gnu::noinline]] bool occluded_4(const pt::WideBvh& bvh, const pt::WideRay& ray, float t_max) {
  return occluded<16>(bvh, ray, t_max);
}
}  // namespace

namespace pt {

WideHit wide_bvh_nearest(const WideBvh& bvh, const WideRay& ray, WideHit best, int lanes) {
  if (bvh.nodes.empty()) return best;
#if PT_WIDE_DISPATCH
  const int l = level(lanes);
  if (l == 2) return wide_walk::nearest_avx512(bvh, ray, best);
  if (l == 1) return wide_walk::nearest_avx2(bvh, ray, best);
#endif
  return nearest_4(bvh, ray, best);
}

bool wide_bvh_occluded(const WideBvh& bvh, const WideRay& ray, float t_max, int lanes) {
  if (bvh.nodes.empty()) return false;
#if PT_WIDE_DISPATCH
  const int l = level(lanes);
  if (l == 2) return wide_walk::occluded_avx512(bvh, ray, t_max);
  if (l == 1) return wide_walk::occluded_avx2(bvh, ray, t_max);
#endif
  return occluded_4(bvh, ray, t_max);
}

}  // namespace pt
#endif
