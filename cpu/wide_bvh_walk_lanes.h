// The CPU walk's tests on SIMD lanes (the step after the article's GPU section, which ends
// "yet without an acceleration structure"): Walk, a ray as the lanes take it, with a node's 8
// boxes tested by box_span() of common/kernel/box_slab.glsl on each lane (grown by the margin
// of the root's box) and a leaf's triangles by hit_triangle_lanes(); and that margin. Part
// of cpu/wide_bvh_walk.cpp, which includes it inside its anonymous namespace, after the
// kernel's constants and triangle_lane_ops.h, once per instruction set: it is not a
// header of its own. Lab 5's answer here (the clamp of the inverse direction and the slab
// test) is marked for tools/make_lab_handout.py, which cuts it from the handout.
#pragma once

template <int bytes> struct Walk {
  using L = Lanes<bytes>;
  using F = typename L::F;
  using I = typename L::I;
  static constexpr int parts = pt::kWideWidth / L::count;

  F o[3], inv[3];  // box_span()'s ray, world axes
  bool back[3];  // per axis, inv < 0 (its sign bit): the box's near side is then its hi
  F grow[3];  // per axis, the root's margin, negated where back: what the near side moves by
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
  // pad: the root's margin (root_pad below), every box's, so known once per ray.
  [[gnu::always_inline]] Walk(const pt::WideRay& ray, float pad) {
#pragma GCC unroll 3
    for (int k = 0; k < 3; k++) {
      const float v = inverse_axis(ray.dir[k]);
      o[k] = lanes_splat<F>(ray.origin[k]), inv[k] = lanes_splat<F>(v);
      back[k] = std::signbit(v);
      grow[k] = lanes_splat<F>(back[k] ? -pad : pad);
    }
    axis[0] = ray.kx, axis[1] = ray.ky, axis[2] = ray.kz;
    tri = LaneRay<bytes>{lanes_splat<F>(ray.origin[ray.kx]), lanes_splat<F>(ray.origin[ray.ky]),
                         lanes_splat<F>(ray.origin[ray.kz]), lanes_splat<F>(ray.sx),
                         lanes_splat<F>(ray.sy),             lanes_splat<F>(ray.sz)};
  }

  // box_span() on the children [at, at + L::count) of n, each grown by the margin of the
  // root's box: the mask of those hit within [0, t_max] (used slots only) and their entry
  // distances. The root's margin is at least each box's own (a box lies in the root's, so its
  // corners are no farther from the origin, and rounding is monotone): the test stays as
  // conservative as box_span(), and the margin is known once per ray, not computed per box.
  [[gnu::always_inline]] I boxes(const pt::WideNode& n, int at, float t_max, F& enter) const {
    F t_enter = F{}, t_exit = lanes_splat<F>(t_max);
    // The slab test on lanes is box_span()'s, lab 5's answer: its handout leaves it out
    // (tools/make_lab_handout.py), and there every used child within [0, t_max] is hit,
    // which finds the same hits, only slower.
    // [lab 5 answer]
    // The sides by the ray's direction: along an axis with inv >= 0 the near side is lo, as
    // box_span()'s t0 < t1 picks it, and a side grown by -pad (lo) is one grown by grow (both
    // exact): the same values as box_span()'s, without its compare and two selects.
    F a_near[3], a_far[3];
#pragma GCC unroll 3
    for (int k = 0; k < 3; k++) {
      a_near[k] = L::load((back[k] ? n.hi[k] : n.lo[k]) + at) - o[k];
      a_far[k] = L::load((back[k] ? n.lo[k] : n.hi[k]) + at) - o[k];
    }
#pragma GCC unroll 3
    for (int k = 0; k < 3; k++) {
      const F near = (a_near[k] - grow[k]) * inv[k];
      const F far = (a_far[k] + grow[k]) * inv[k] * kBoxRoundUp;
      t_enter = near > t_enter ? near : t_enter;
      t_exit = far < t_exit ? far : t_exit;
    }
    // [/lab 5 answer]
    I child;
    __builtin_memcpy(&child, n.child + at, sizeof child);
    enter = t_enter;
    return (t_enter <= t_exit) & (child != pt::kWideEmpty);
  }

  // The mask of the 8 children hit (grown by the root's margin), one bit each, and their
  // entry distances.
  [[gnu::always_inline]] unsigned children(const pt::WideNode& n, float t_max, float* enter) const {
    unsigned bits = 0u;
    for (int p = 0; p < parts; p++) {
      F e;
      const I hit = boxes(n, p * L::count, t_max, e);
      __builtin_memcpy(enter + p * L::count, &e, sizeof e);
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

// The margin of the root's box, box_span()'s for that box: every box is grown by it.
[[gnu::always_inline]] inline float root_pad(const pt::WideBvh& bvh, const pt::WideRay& ray) {
  float m[3];
  for (int k = 0; k < 3; k++) {
    const float a_lo = bvh.root_lo[k] - ray.origin[k], a_hi = bvh.root_hi[k] - ray.origin[k];
    m[k] = larger(abs(a_lo), abs(a_hi));
  }
  return kBoxPad * (m[0] + m[1] + m[2]);
}
