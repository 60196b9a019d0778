// hit_triangle() of common/kernel/intersect.glsl (the article's raycasting test, Eq. 2) on
// several triangles at once, one per SIMD lane (GCC's vector extensions), with exactly its
// operations: the shared lane code of the CPU's two fast searches, the brute force over
// pt::TriangleSoa (triangle_lanes.h) and the leaves of the wide BVH (wide_bvh_walk.cpp, the
// CPU's form of the BVH that follows the article's GPU section). C++ only. No include guard:
// it is included inside a kernel's namespace by triangle_lanes.h (whose guard covers it) and
// inside wide_bvh_walk.cpp's; it needs Hit, kGamma* and kPrimTriangle there.

// `bytes` of floats side by side, and the matching lane masks (-1 or 0 per lane) and indices.
template <int bytes> struct Lanes {
  using Int = std::conditional_t<sizeof(float) == 4, std::int32_t, std::int64_t>;
  typedef float F __attribute__((vector_size(bytes)));
  typedef Int I __attribute__((vector_size(bytes)));
  static constexpr int count = bytes / int(sizeof(float));
  [[gnu::always_inline]] static F load(const float* p) {
    F v;
    __builtin_memcpy(&v, p, sizeof v);
    return v;
  }
};

// abs(), max() and min() as the scalar code computes them (kernel_prelude.h's abs, glm's max
// and min), on every lane.
template <class F> [[gnu::always_inline]] inline F lanes_abs(F x) {
  using L = Lanes<int(sizeof(F))>;
  typename L::I bits;
  __builtin_memcpy(&bits, &x, sizeof x);
  bits &= std::numeric_limits<typename L::Int>::max();  // every bit but the sign
  __builtin_memcpy(&x, &bits, sizeof x);
  return x;
}
template <class F> [[gnu::always_inline]] inline F lanes_max(F x, F y) {
  return x < y ? y : x;
}
template <class F> [[gnu::always_inline]] inline F lanes_min(F x, F y) {
  return y < x ? y : x;
}

// f folded over the lanes (f(x, y) must be the same as f(y, x)): every lane ends up with
// f of all of them. 8 or 4 lanes (2 for the double-precision test build). f is one of the
// folds below, not a lambda: a lambda is inlined only by the optimiser, and at -O0 a call
// to it from an AVX2 function passes 32-byte vectors in the other ABI, so that the lanes'
// nearest hit came out wrong (a hit at t = 0 found by the -O0 check build's
// test_triangle_lanes.cpp, issue #51).
template <class V, class Fn> [[gnu::always_inline]] inline V lanes_fold(V x, Fn f) {
  constexpr int n = int(sizeof(V) / sizeof(x[0]));
  static_assert(n == 8 || n == 4 || n == 2);
  if constexpr (n == 8) {
    x = f(x, __builtin_shufflevector(x, x, 4, 5, 6, 7, 0, 1, 2, 3));
    x = f(x, __builtin_shufflevector(x, x, 2, 3, 0, 1, 6, 7, 4, 5));
    return f(x, __builtin_shufflevector(x, x, 1, 0, 3, 2, 5, 4, 7, 6));
  } else if constexpr (n == 4) {
    x = f(x, __builtin_shufflevector(x, x, 2, 3, 0, 1));
    return f(x, __builtin_shufflevector(x, x, 1, 0, 3, 2));
  } else {
    return f(x, __builtin_shufflevector(x, x, 1, 0));
  }
}

// The folds of nearest_of_lanes, inlined at every optimisation level.
struct LanesMinFold {
  template <class V> [[gnu::always_inline]] V operator()(V x, V y) const { return lanes_min(x, y); }
};
struct LanesOrFold {
  template <class V> [[gnu::always_inline]] V operator()(V x, V y) const { return x | y; }
};

// x on every lane, bit for bit: x - 0 is x for every x, -0 included (0 + x would make it +0).
template <class F> [[gnu::always_inline]] inline F lanes_splat(float x) {
  return x - F{};
}

// Whether any lane's mask is set.
template <class I> [[gnu::always_inline]] inline bool any_lane(I mask) {
  std::uint64_t words[sizeof(I) / 8];
  __builtin_memcpy(words, &mask, sizeof(I));
  std::uint64_t any = 0;
  for (std::uint64_t word : words) any |= word;
  return any != 0;
}

// The ray as hit_triangle() uses it, on every lane: its origin and shear in the ray's own
// axis order (RayShear's kx, ky, kz).
template <int bytes> struct LaneRay {
  typename Lanes<bytes>::F ox, oy, oz, sx, sy, sz;
};

// Per lane: the nearest hit so far, its barycentrics and its triangle (-1: none yet).
template <int bytes> struct LaneNearest {
  typename Lanes<bytes>::F t, b1, b2;
  typename Lanes<bytes>::I index;
};

// hit_triangle() on every lane, for the triangles whose coordinates lie in q[3 v + k] + at
// (vertex v, ray axis k: kx, ky, kz) and whose indices are `index`: each lane keeps the
// nearer of its own hit and near. by_index: a hit at the same t as the lane's also replaces
// it when its index is lower (the BVH meets triangles out of index order); else only a
// nearer hit does (the loop in index order). Returns false when no lane can have changed.
template <int bytes, bool by_index>
[[gnu::always_inline]] inline bool hit_triangle_lanes(const LaneRay<bytes>& r, const float* const* q, std::size_t at,
                                                      typename Lanes<bytes>::I index, LaneNearest<bytes>& near) {
  using L = Lanes<bytes>;
  using F = typename L::F;
  using I = typename L::I;
  const F zero = F{};
  // The operations of hit_triangle(), in the same order: the same roundings.
  const F ax0 = L::load(q[0] + at) - r.ox, ay0 = L::load(q[1] + at) - r.oy, az0 = L::load(q[2] + at) - r.oz;
  const F bx0 = L::load(q[3] + at) - r.ox, by0 = L::load(q[4] + at) - r.oy, bz0 = L::load(q[5] + at) - r.oz;
  const F cx0 = L::load(q[6] + at) - r.ox, cy0 = L::load(q[7] + at) - r.oy, cz0 = L::load(q[8] + at) - r.oz;
  const F ax = ax0 - r.sx * az0, ay = ay0 - r.sy * az0;
  const F bx = bx0 - r.sx * bz0, by = by0 - r.sy * bz0;
  const F cx = cx0 - r.sx * cz0, cy = cy0 - r.sy * cz0;
  const F u = cx * by - cy * bx;
  const F v = ax * cy - ay * cx;
  const F w = bx * ay - by * ax;
  // Outside: some edge function below 0 and some above. By min and max, which differ
  // from hit_triangle()'s comparisons only when one is NaN; then t is NaN too and the
  // triangle is missed either way.
  const I outside = (lanes_min(lanes_min(u, v), w) < zero) & (lanes_max(lanes_max(u, v), w) > zero);
  const F det = u + v + w;
  const F az = r.sz * az0, bz = r.sz * bz0, cz = r.sz * cz0;
  const F t_scaled = u * az + v * bz + w * cz;
  const F inv_det = 1.0f / det;
  const F t = t_scaled * inv_det;
  I closer = t < near.t;
  if constexpr (by_index) closer |= (t == near.t) & (index < near.index);
  I hit = ~outside & (det != zero) & (t > zero) & closer;
  if (!any_lane(hit)) return false;  // the usual case: the rounding bounds only where a lane hit
  const F max_x = lanes_max(lanes_max(lanes_abs(ax), lanes_abs(bx)), lanes_abs(cx));
  const F max_y = lanes_max(lanes_max(lanes_abs(ay), lanes_abs(by)), lanes_abs(cy));
  const F max_z = lanes_max(lanes_max(lanes_abs(az), lanes_abs(bz)), lanes_abs(cz));
  const F max_e = lanes_max(lanes_max(lanes_abs(u), lanes_abs(v)), lanes_abs(w));
  const F delta_x = kGamma5 * (max_x + max_z);
  const F delta_y = kGamma5 * (max_y + max_z);
  const F delta_z = kGamma3 * max_z;
  const F delta_e = 2.0f * (kGamma2 * max_x * max_y + delta_y * max_x + delta_x * max_y);
  const F delta_t = 3.0f * (kGamma3 * max_e * max_z + delta_e * max_z + delta_z * max_e) * lanes_abs(inv_det);
  const F extent =
      lanes_max(lanes_max(lanes_max(lanes_abs(ax0), lanes_abs(ay0)), lanes_max(lanes_abs(az0), lanes_abs(bx0))),
                lanes_max(lanes_max(lanes_abs(by0), lanes_abs(bz0)),
                          lanes_max(lanes_max(lanes_abs(cx0), lanes_abs(cy0)), lanes_abs(cz0))));
  hit &= ~(t <= delta_t) & ~(t <= 4e-7f * extent);
  near.t = hit ? t : near.t;
  near.b1 = hit ? v * inv_det : near.b1;
  near.b2 = hit ? w * inv_det : near.b2;
  near.index = hit ? index : near.index;
  return true;
}

// The nearest of the lanes; of equal distances, the lower index; `best` when no lane holds a
// triangle. Without branches: the minimum over the lanes by swapping halves, quarters, ...
// (lanes_fold), first of t, then of the indices at that t.
template <int bytes> [[gnu::always_inline]] inline Hit nearest_of_lanes(const LaneNearest<bytes>& near, Hit best) {
  using L = Lanes<bytes>;
  using F = typename L::F;
  using I = typename L::I;
  using Int = typename L::Int;
  const F t = lanes_fold(near.t, LanesMinFold{});
  const I at_t = (near.t == t) & (near.index >= 0);
  const I index_at_t = at_t ? near.index : I{} + std::numeric_limits<Int>::max();
  const I nearest = lanes_fold(index_at_t, LanesMinFold{});
  if (nearest[0] == std::numeric_limits<Int>::max()) return best;
  // Its barycentrics: the bits of the one lane that holds it, the others masked to 0.
  const I pick = near.index == nearest;
  I b1, b2;
  __builtin_memcpy(&b1, &near.b1, sizeof b1);
  __builtin_memcpy(&b2, &near.b2, sizeof b2);
  b1 = lanes_fold(b1 & pick, LanesOrFold{});
  b2 = lanes_fold(b2 & pick, LanesOrFold{});
  float b1_bits, b2_bits;
  const Int b1_0 = b1[0], b2_0 = b2[0];
  __builtin_memcpy(&b1_bits, &b1_0, sizeof b1_bits);
  __builtin_memcpy(&b2_bits, &b2_0, sizeof b2_bits);
  return Hit(t[0], b1_bits, b2_bits, uint(nearest[0]), kPrimTriangle);
}
