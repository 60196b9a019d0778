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

#include "cpu/triangle_lane_ops.h"

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
  const int axis[3] = {rs.kx, rs.ky, rs.kz};
  const float* q[9];
  for (int v = 0; v < 3; v++) {
    for (int k = 0; k < 3; k++) q[3 * v + k] = triangle_soa + std::size_t(3 * v + axis[k]) * stride;
  }
  const float origin[3] = {ray.origin.x, ray.origin.y, ray.origin.z};
  const LaneRay<bytes> r{lanes_splat<F>(origin[rs.kx]), lanes_splat<F>(origin[rs.ky]), lanes_splat<F>(origin[rs.kz]),
                         lanes_splat<F>(rs.s.x),        lanes_splat<F>(rs.s.y),        lanes_splat<F>(rs.s.z)};
  LaneNearest<bytes> near{lanes_splat<F>(best.t), F{}, F{}, I{} - 1};
  I index;
  static constexpr typename L::Int iota[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  __builtin_memcpy(&index, iota, sizeof index);
  for (std::size_t base = 0u; base < n; base += std::size_t(L::count), index += L::count) {
    hit_triangle_lanes<bytes, false>(r, q, base, index, near);
  }
  return nearest_of_lanes<bytes>(near, best);
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

// The wide BVH's walk tests boxes as common/kernel/box_slab.glsl does: a kernel built with
// another slab test (lab 5's, labs/lab5.glsl) walks the binary tree with its own.
#undef PT_CPU_WIDE_WALK  // a kernel compiled twice in one file (test_float_double.cpp)
#ifdef PT_BOX_SLAB_GLSL
#define PT_CPU_WIDE_WALK 1
#else
#define PT_CPU_WIDE_WALK 0
#endif

// The ray as the wide BVH's walk takes it (wide_bvh.h). Assignments, not braces: in the
// double-precision test build `float` is double here (that build never binds a wide tree).
pt::WideRay wide_ray(Ray ray, RayShear rs) {
  pt::WideRay r;
  for (int k = 0; k < 3; k++) r.origin[k] = ray.origin[k], r.dir[k] = ray.dir[k];
  r.kx = rs.kx, r.ky = rs.ky, r.kz = rs.kz;
  r.sx = rs.s.x, r.sy = rs.s.y, r.sz = rs.s.z;
  return r;
}

// The nearest hit of `best` and every triangle through the wide BVH (wide_bvh_walk.cpp).
Hit nearest_triangle_wide(Ray ray, RayShear rs, Hit best) {
  pt::WideHit in;
  in.t = best.t, in.b1 = best.b1, in.b2 = best.b2;
  in.prim = best.kind == kPrimTriangle ? std::int32_t(best.prim) : -1;
  const pt::WideHit h = pt::wide_bvh_nearest(*wide_bvh, wide_ray(ray, rs), in);
  if (h.prim < 0 || (h.prim == in.prim && best.kind == kPrimTriangle)) return best;
  return Hit(h.t, h.b1, h.b2, uint(h.prim), kPrimTriangle);
}

// The CPU's nearest_triangle() (declared in intersect.glsl): the BVH when the pass asks for
// it and the render built one (the wide tree's SIMD walk, else common/kernel/bvh.glsl's
// binary walk), else the SIMD lanes when the triangles are also laid out as arrays, else
// the loop in index order; the same hits.
// PT_CPU_RAY_LOG(ray, t_max, any_hit), when defined, sees every ray a kernel traces: the
// bench's copy of a stage that records them (bench/accel_stage_rays.cpp); never in a stage.
#ifndef PT_CPU_RAY_LOG
#define PT_CPU_RAY_LOG(ray, t_max, any_hit)
#endif
Hit nearest_triangle(Ray ray, RayShear rs, Hit best) {
  PT_CPU_RAY_LOG(ray, best.t, false);
  if (PT_CPU_WIDE_WALK && params.accel == kAccelBvh && wide_bvh != nullptr) return nearest_triangle_wide(ray, rs, best);
  if (params.accel == kAccelBvh && bvh_nodes != nullptr) return nearest_triangle_bvh(ray, rs, best);
  if (triangle_soa != nullptr) return hit_triangles_blocked(ray, rs, best);
  return nearest_triangle_in_order(ray, rs, best);
}

// The CPU's occluded_triangles() (declared in intersect.glsl): the BVH's any-hit walk, else
// whether the search above finds a hit.
bool occluded_triangles(Ray ray, RayShear rs, float t_max) {
  if (PT_CPU_WIDE_WALK && params.accel == kAccelBvh && wide_bvh != nullptr) {
    PT_CPU_RAY_LOG(ray, t_max, true);
    return pt::wide_bvh_occluded(*wide_bvh, wide_ray(ray, rs), t_max);
  }
  if (params.accel == kAccelBvh && bvh_nodes != nullptr) return occluded_bvh(ray, rs, t_max);
  return nearest_triangle(ray, rs, Hit(t_max, 0.0f, 0.0f, 0u, kPrimNone)).kind != kPrimNone;
}

#endif  // PT_CPU_TRIANGLE_LANES_H
