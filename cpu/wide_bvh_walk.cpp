// The walk of the CPU's wide BVH (wide_bvh.h; the step after the article's GPU section,
// which ends "yet without an acceleration structure"): a node's 8 boxes by one slab test on
// SIMD lanes, box_span() of common/kernel/box_slab.glsl on each lane with the margin of the
// node's own box, no smaller than each child's (the same rounding up, so never a miss where
// the binary walk would not miss), the hit
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

template <int bytes> struct Walk {
  using L = Lanes<bytes>;
  using F = typename L::F;
  using I = typename L::I;
  static constexpr int parts = pt::kWideWidth / L::count;

  F o[3], inv[3];  // box_span()'s ray, world axes
  I flip[3];  // per axis, the sign bit of inv (all lanes): the box's near side is then its hi
  bool back[3];  // the same as bools
  LaneRay<bytes> tri;  // hit_triangle()'s ray, the ray's axes
  int axis[3];

  // box_slab.glsl's inverse_direction() for one axis, the same operations (glm's clamp:
  // max, then min, a NaN kept), written here so that it is inlined into the walk of each
  // instruction set. Called instead, the kernel's function (plain SSE code, built once)
  // cost a third of the CPU time of every stage on the Cornell box on an AVX-512 machine,
  // most likely for going from AVX code to SSE code and back per ray (docs/acceleration.md,
  // "Measured"). Its clamp is lab 5's answer and is cut from the handout, as the slab test
  // below is.
  [[gnu::always_inline]] static float inverse_axis(float d) {
    float v = 1.0f / d;
    // [lab 5 answer]
    v = v < -kInfinity ? -kInfinity : v;
    v = kInfinity < v ? kInfinity : v;
    // [/lab 5 answer]
    return v;
  }

  // The loops over the 3 axes are unrolled (#pragma GCC unroll): GCC kept them as loops, and
  // the slab test's differences then went through the stack at every node; unrolled they
  // stay in registers, the same operations (0.87 to 0.90 of the walk's CPU time, issue 50).
  [[gnu::always_inline]] explicit Walk(const pt::WideRay& ray) {
#pragma GCC unroll 3
    for (int k = 0; k < 3; k++) {
      const float v = inverse_axis(ray.dir[k]);
      o[k] = lanes_splat<F>(ray.origin[k]), inv[k] = lanes_splat<F>(v);
      back[k] = std::signbit(v);
      flip[k] = I{} + (back[k] ? std::int32_t(0x80000000u) : 0);
    }
    axis[0] = ray.kx, axis[1] = ray.ky, axis[2] = ray.kz;
    tri = LaneRay<bytes>{lanes_splat<F>(ray.origin[ray.kx]), lanes_splat<F>(ray.origin[ray.ky]),
                         lanes_splat<F>(ray.origin[ray.kz]), lanes_splat<F>(ray.sx),
                         lanes_splat<F>(ray.sy),             lanes_splat<F>(ray.sz)};
  }

  // box_span() on the children [at, at + L::count) of n, each grown by `pad`, the margin of
  // n's own box: the mask of those hit within [0, t_max] (used slots only), their entry
  // distances, and each child's own margin (child_pad), for its children. n's margin is at
  // least each child's (a child's box lies in n's, so its corners are no farther from the
  // origin, and rounding is monotone): the test stays as conservative as box_span(). And it
  // is known before n is read, so the slab test no longer waits on the margin's 5 steps on
  // the way from one node to the next; the children's margins are computed beside it.
  [[gnu::always_inline]] I boxes(const pt::WideNode& n, int at, float t_max, [[maybe_unused]] F pad, F& enter,
                                 F& child_pad) const {
    F t_enter = F{}, t_exit = lanes_splat<F>(t_max);
    child_pad = F{};
    // The slab test on lanes is box_span()'s, lab 5's answer: its handout leaves it out
    // (tools/make_lab_handout.py), and there every used child within [0, t_max] is hit,
    // which finds the same hits, only slower.
    // [lab 5 answer]
    // The sides by the ray's direction: along an axis with inv >= 0 the near side is lo, as
    // box_span()'s t0 < t1 picks it, and a side grown by -pad (lo) is one grown by pad ^ sign
    // (both exact): the same values as box_span()'s, without its compare and two selects.
    F a_near[3], a_far[3];
#pragma GCC unroll 3
    for (int k = 0; k < 3; k++) {
      a_near[k] = L::load((back[k] ? n.hi[k] : n.lo[k]) + at) - o[k];
      a_far[k] = L::load((back[k] ? n.lo[k] : n.hi[k]) + at) - o[k];
    }
    child_pad = kBoxPad * (lanes_max(lanes_abs(a_near[0]), lanes_abs(a_far[0])) +
                           lanes_max(lanes_abs(a_near[1]), lanes_abs(a_far[1])) +
                           lanes_max(lanes_abs(a_near[2]), lanes_abs(a_far[2])));
    I pad_bits;
    __builtin_memcpy(&pad_bits, &pad, sizeof pad_bits);
#pragma GCC unroll 3
    for (int k = 0; k < 3; k++) {
      F grow;
      const I bits = pad_bits ^ flip[k];
      __builtin_memcpy(&grow, &bits, sizeof grow);
      const F near = (a_near[k] - grow) * inv[k];
      const F far = (a_far[k] + grow) * inv[k] * kBoxRoundUp;
      t_enter = near > t_enter ? near : t_enter;
      t_exit = far < t_exit ? far : t_exit;
    }
    // [/lab 5 answer]
    I child;
    __builtin_memcpy(&child, n.child + at, sizeof child);
    enter = t_enter;
    return (t_enter <= t_exit) & (child != pt::kWideEmpty);
  }

  // The mask of the 8 children hit (grown by pad, n's margin), one bit each, their entry
  // distances and their margins.
  [[gnu::always_inline]] unsigned children(const pt::WideNode& n, float t_max, float pad, float* enter,
                                           float* pads) const {
    unsigned bits = 0u;
    const F grow = lanes_splat<F>(pad);
    for (int p = 0; p < parts; p++) {
      F e, c;
      const I hit = boxes(n, p * L::count, t_max, grow, e, c);
      __builtin_memcpy(enter + p * L::count, &e, sizeof e);
      __builtin_memcpy(pads + p * L::count, &c, sizeof c);
      bits |= lane_bits(hit) << (p * L::count);
    }
    return bits;
  }

  // One bit per lane of a mask: the sign bits by one instruction (SSE's movmskps on 4 lanes,
  // AVX's vmovmskps on 8, which this copy may use when it is compiled for AVX2), else each
  // lane's weight or-ed over the lanes (a permute, two shuffles and three ors: 14% of the
  // walk's time on 8 lanes when the copies shared one compilation, issue 50).
  [[gnu::always_inline]] static unsigned lane_bits(I hit) {
#if PT_WIDE_DISPATCH
    F f;
    __builtin_memcpy(&f, &hit, sizeof f);
    if constexpr (bytes == 16) return unsigned(_mm_movemask_ps(f));
#if PT_WIDE_WALK_ISA > 0
    if constexpr (bytes == 32) return unsigned(_mm256_movemask_ps(f));
#endif
#endif
    static constexpr typename L::Int weight[8] = {1, 2, 4, 8, 16, 32, 64, 128};
    I w;
    __builtin_memcpy(&w, weight, sizeof w);
    return unsigned(lanes_fold(hit & w, LanesOrFold{})[0]);
  }

  // The leaf block's triangles against `best` (by_index: the tie rule of the nearest hit).
  template <bool by_index> [[gnu::always_inline]] Hit leaf(const pt::WideBlock& b, Hit best) const {
    const float* q[9];
#pragma GCC unroll 3
    for (int v = 0; v < 3; v++) {
#pragma GCC unroll 3
      for (int k = 0; k < 3; k++) q[3 * v + k] = b.v[3 * v + axis[k]];
    }
    for (int p = 0; p < parts; p++) {
      if (p > 0 && b.index[p * L::count] < 0) break;  // the rest of the block is empty
      I index;
      __builtin_memcpy(&index, b.index + p * L::count, sizeof index);
      const typename L::Int held = by_index && best.kind == kPrimTriangle ? typename L::Int(best.prim) : -1;
      LaneNearest<bytes> near{lanes_splat<F>(best.t), lanes_splat<F>(best.b1), lanes_splat<F>(best.b2), I{} + held};
      if (hit_triangle_lanes<bytes, by_index>(tri, q, std::size_t(p * L::count), index, near))
        best = nearest_of_lanes<bytes>(near, best);
    }
    return best;
  }
};

// The margin of the root's box, box_span()'s for that box: the root's children are grown by it.
[[gnu::always_inline]] inline float root_pad(const pt::WideBvh& bvh, const pt::WideRay& ray) {
  float m[3];
  for (int k = 0; k < 3; k++) {
    const float a_lo = bvh.root_lo[k] - ray.origin[k], a_hi = bvh.root_hi[k] - ray.origin[k];
    m[k] = larger(abs(a_lo), abs(a_hi));
  }
  return kBoxPad * (m[0] + m[1] + m[2]);
}

template <int bytes>
[[gnu::always_inline]] inline pt::WideHit nearest(const pt::WideBvh& bvh, const pt::WideRay& ray, pt::WideHit in) {
  const Walk<bytes> walk(ray);
  Hit best(in.t, in.b1, in.b2, uint(in.prim), in.prim >= 0 ? kPrimTriangle : kPrimNone);
  std::int32_t stack_ref[kWideStack];
  float stack_t[kWideStack], stack_pad[kWideStack];
  int top = 0;
  std::int32_t ref = 0;
  float pad = root_pad(bvh, ray);  // the margin of ref's box
  while (true) {
    if (ref >= 0) {
      const pt::WideNode& n = bvh.nodes[std::size_t(ref)];
      float enter[pt::kWideWidth], pads[pt::kWideWidth];
      unsigned bits = walk.children(n, best.t, pad, enter, pads);
      if (bits != 0u) {
        int i = __builtin_ctz(bits);
        bits &= bits - 1u;
        if (bits == 0u) {
          ref = n.child[i], pad = pads[i];
          continue;
        }
        // Two or more: all on the stack, nearest last (insertion by entry distance), and
        // the nearest taken straight off again.
        const int base = top;
        for (;; i = __builtin_ctz(bits), bits &= bits - 1u) {
          int j = top++;
          for (; j > base && stack_t[j - 1] < enter[i]; j--)
            stack_ref[j] = stack_ref[j - 1], stack_t[j] = stack_t[j - 1], stack_pad[j] = stack_pad[j - 1];
          stack_ref[j] = n.child[i], stack_t[j] = enter[i], stack_pad[j] = pads[i];
          if (bits == 0u) break;
        }
        --top, ref = stack_ref[top], pad = stack_pad[top];
        continue;
      }
    } else {
      best = walk.template leaf<true>(bvh.blocks[std::size_t(~ref)], best);
    }
    // Nothing below: the next pending child that a hit could still lie in.
    while (top > 0 && !(stack_t[top - 1] <= best.t)) top--;
    if (top == 0) break;
    --top, ref = stack_ref[top], pad = stack_pad[top];
  }
  if (best.kind != kPrimTriangle) return in;
  return pt::WideHit{best.t, best.b1, best.b2, std::int32_t(best.prim)};
}

template <int bytes>
[[gnu::always_inline]] inline bool occluded(const pt::WideBvh& bvh, const pt::WideRay& ray, float t_max) {
  const Walk<bytes> walk(ray);
  const Hit none(t_max, 0.0f, 0.0f, 0u, kPrimNone);
  std::int32_t stack_ref[kWideStack];
  float stack_pad[kWideStack];
  int top = 0;
  stack_ref[top] = 0, stack_pad[top++] = root_pad(bvh, ray);
  while (top > 0) {
    --top;
    const std::int32_t ref = stack_ref[top];
    if (ref >= 0) {
      const pt::WideNode& n = bvh.nodes[std::size_t(ref)];
      float enter[pt::kWideWidth], pads[pt::kWideWidth];
      for (unsigned bits = walk.children(n, t_max, stack_pad[top], enter, pads); bits != 0u; bits &= bits - 1u) {
        const int i = __builtin_ctz(bits);
        stack_ref[top] = n.child[i], stack_pad[top++] = pads[i];
      }
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
