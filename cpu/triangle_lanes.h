// The CPU's fast path through the brute-force triangle loop of intersect.glsl (the article's
// raycasting step, Eq. 2, is this search for the nearest surface). C++ only: a GLSL compiler
// never sees it. The triangles are also kept as a structure of arrays (one array per vertex
// and axis, padded to a multiple of 8 with empty triangles; pt::TriangleSoa), and each ray
// tests several triangles at once, one per SIMD lane (GCC's vector extensions: 8 lanes
// where the CPU has AVX2, else 4), with exactly the operations of hit_triangle(). Every lane
// keeps the nearest hit among its own triangles; the nearest of the lanes, the lower index
// on a tie, is then what the loop over hit_triangle() finds, since that loop also keeps the
// nearest hit whatever the order. Same t, barycentrics and triangle, bit for bit
// (tests/cpu/test_triangle_lanes.cpp). Why this layout: docs/results.md, "Speed targets".
// Included after common/kernel/intersect.glsl (kernel_end.h), whose nearest_triangle() it defines.
#ifndef PT_CPU_TRIANGLE_LANES_H
#define PT_CPU_TRIANGLE_LANES_H

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
// f of all of them. 8 or 4 lanes (2 for the double-precision test build).
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

// Whether any lane's mask is set.
template <class I> [[gnu::always_inline]] inline bool any_lane(I mask) {
  std::uint64_t words[sizeof(I) / 8];
  __builtin_memcpy(words, &mask, sizeof(I));
  std::uint64_t any = 0;
  for (std::uint64_t word : words) any |= word;
  return any != 0;
}

// The nearest hit of `best` and triangles [0, n): hit_triangle() on every lane.
template <int bytes>
[[gnu::always_inline]] inline Hit nearest_triangle_lanes(Ray ray, RayShear rs, Hit best) {
  using L = Lanes<bytes>;
  using F = typename L::F;
  using I = typename L::I;
  const std::size_t n = params.triangle_count;
  const std::size_t stride = triangle_soa_stride;
  // Array (vertex v, axis k) starts at triangle_soa + (3 v + k) stride; the ray's axes are
  // chosen once here, so the loop below indexes nothing at run time.
  const float* p0x = triangle_soa + (0u + uint(rs.kx)) * stride;
  const float* p0y = triangle_soa + (0u + uint(rs.ky)) * stride;
  const float* p0z = triangle_soa + (0u + uint(rs.kz)) * stride;
  const float* p1x = triangle_soa + (3u + uint(rs.kx)) * stride;
  const float* p1y = triangle_soa + (3u + uint(rs.ky)) * stride;
  const float* p1z = triangle_soa + (3u + uint(rs.kz)) * stride;
  const float* p2x = triangle_soa + (6u + uint(rs.kx)) * stride;
  const float* p2y = triangle_soa + (6u + uint(rs.ky)) * stride;
  const float* p2z = triangle_soa + (6u + uint(rs.kz)) * stride;
  const F zero = F{};
  const float origin[3] = {ray.origin.x, ray.origin.y, ray.origin.z};
  const F ox = zero + origin[rs.kx], oy = zero + origin[rs.ky], oz = zero + origin[rs.kz];
  const F sx = zero + rs.s.x, sy = zero + rs.s.y, sz = zero + rs.s.z;
  // Per lane: the nearest hit so far and its triangle (-1: none yet).
  F near_t = zero + best.t, near_b1 = zero, near_b2 = zero;
  I near_index = I{} - 1, index;
  static constexpr typename L::Int iota[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  __builtin_memcpy(&index, iota, sizeof index);
  for (std::size_t base = 0u; base < n; base += std::size_t(L::count), index += L::count) {
    // The operations of hit_triangle(), in the same order: the same roundings.
    const F ax0 = L::load(p0x + base) - ox, ay0 = L::load(p0y + base) - oy, az0 = L::load(p0z + base) - oz;
    const F bx0 = L::load(p1x + base) - ox, by0 = L::load(p1y + base) - oy, bz0 = L::load(p1z + base) - oz;
    const F cx0 = L::load(p2x + base) - ox, cy0 = L::load(p2y + base) - oy, cz0 = L::load(p2z + base) - oz;
    const F ax = ax0 - sx * az0, ay = ay0 - sy * az0;
    const F bx = bx0 - sx * bz0, by = by0 - sy * bz0;
    const F cx = cx0 - sx * cz0, cy = cy0 - sy * cz0;
    const F u = cx * by - cy * bx;
    const F v = ax * cy - ay * cx;
    const F w = bx * ay - by * ax;
    // Outside: some edge function below 0 and some above. By min and max, which differ
    // from hit_triangle()'s comparisons only when one is NaN; then t is NaN too and the
    // triangle is missed either way.
    const I outside = (lanes_min(lanes_min(u, v), w) < zero) & (lanes_max(lanes_max(u, v), w) > zero);
    const F det = u + v + w;
    const F az = sz * az0, bz = sz * bz0, cz = sz * cz0;
    const F t_scaled = u * az + v * bz + w * cz;
    const F inv_det = 1.0f / det;
    const F t = t_scaled * inv_det;
    I hit = ~outside & (det != zero) & (t > zero) & (t < near_t);
    if (!any_lane(hit)) continue;  // the usual case: the rounding bounds only where a lane hit
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
    near_t = hit ? t : near_t;
    near_b1 = hit ? v * inv_det : near_b1;
    near_b2 = hit ? w * inv_det : near_b2;
    near_index = hit ? index : near_index;
  }
  // The nearest of the lanes; of equal distances, the lower index. Without branches: the
  // minimum over the lanes by swapping halves, quarters, ... (lanes_fold), first of t, then
  // of the indices at that t.
  using Int = typename L::Int;
  const F t = lanes_fold(near_t, [](F x, F y) { return lanes_min(x, y); });
  const I at_t = (near_t == t) & (near_index >= 0);
  const I index_at_t = at_t ? near_index : I{} + std::numeric_limits<Int>::max();
  const I nearest = lanes_fold(index_at_t, [](I x, I y) { return y < x ? y : x; });
  if (nearest[0] == std::numeric_limits<Int>::max()) return best;
  // Its barycentrics: the bits of the one lane that holds it, the others masked to 0.
  const I pick = near_index == nearest;
  I b1, b2;
  __builtin_memcpy(&b1, &near_b1, sizeof b1);
  __builtin_memcpy(&b2, &near_b2, sizeof b2);
  b1 = lanes_fold(b1 & pick, [](I x, I y) { return x | y; });
  b2 = lanes_fold(b2 & pick, [](I x, I y) { return x | y; });
  float b1_bits, b2_bits;
  const Int b1_0 = b1[0], b2_0 = b2[0];
  __builtin_memcpy(&b1_bits, &b1_0, sizeof b1_bits);
  __builtin_memcpy(&b2_bits, &b2_0, sizeof b2_bits);
  return Hit(t[0], b1_bits, b2_bits, uint(nearest[0]), kPrimTriangle);
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
[[gnu::target("avx2")]] inline Hit nearest_triangle_avx2(Ray ray, RayShear rs, Hit best) {
  return nearest_triangle_lanes<32>(ray, rs, best);
}
// The same 8 lanes with AVX-512's 32 vector registers instead of 16: fewer values go to memory.
[[gnu::target("avx2,avx512f,avx512vl")]] inline Hit nearest_triangle_avx512(Ray ray, RayShear rs, Hit best) {
  return nearest_triangle_lanes<32>(ray, rs, best);
}
#endif

// The nearest hit of `best` and every triangle, as the loop over hit_triangle() finds it.
Hit hit_triangles_blocked(Ray ray, RayShear rs, Hit best) {
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
  static const int level = __builtin_cpu_supports("avx512vl") ? 2 : __builtin_cpu_supports("avx2") ? 1 : 0;
  if (level == 2) return nearest_triangle_avx512(ray, rs, best);
  if (level == 1) return nearest_triangle_avx2(ray, rs, best);
#endif
  return nearest_triangle_lanes<16>(ray, rs, best);
}

// The CPU's nearest_triangle() (declared in intersect.glsl): the BVH (common/kernel/bvh.glsl)
// when the pass asks for it and the render built one, else the SIMD lanes when the
// triangles are also laid out as arrays, else the loop in index order; the same hits.
Hit nearest_triangle(Ray ray, RayShear rs, Hit best) {
  if (params.accel == kAccelBvh && bvh_nodes != nullptr) return nearest_triangle_bvh(ray, rs, best);
  if (triangle_soa != nullptr) return hit_triangles_blocked(ray, rs, best);
  return nearest_triangle_in_order(ray, rs, best);
}

// The CPU's occluded_triangles() (declared in intersect.glsl): the BVH's any-hit walk, else
// whether the search above finds a hit.
bool occluded_triangles(Ray ray, RayShear rs, float t_max) {
  if (params.accel == kAccelBvh && bvh_nodes != nullptr) return occluded_bvh(ray, rs, t_max);
  return nearest_triangle(ray, rs, Hit(t_max, 0.0f, 0.0f, 0u, kPrimNone)).kind != kPrimNone;
}

#endif  // PT_CPU_TRIANGLE_LANES_H
