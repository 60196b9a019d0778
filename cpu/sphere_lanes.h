// The CPU's fast path through the loop over spheres of intersect.glsl (the article's
// raycasting step, Eq. 2, for the scene's spheres): the spheres also kept as a structure of
// arrays (pt::SphereSoa, with the terms of sphere_power_from_world_origin() that depend on
// the sphere alone), and each ray tested against several spheres at once, one per SIMD lane
// (GCC's vector extensions: 8 lanes where the CPU has AVX2, else 4), with exactly the
// operations of hit_sphere(). Every lane keeps the nearest hit among its own spheres; the
// nearest of the lanes, the lower index on a tie, is what the loop over hit_sphere() finds,
// since that loop keeps the first of the nearest. Same t and sphere, bit for bit
// (tests/cpu/test_sphere_lanes.cpp). Why: smallpt's scene is nine spheres, six of them walls
// that nearly every ray meets, and the scalar test was a third of stage5's time there.
// Included after common/kernel/intersect.glsl (kernel_support.h), whose nearest_sphere() it
// defines. C++ only: a GLSL compiler never sees it.
#ifndef PT_CPU_SPHERE_LANES_H
#define PT_CPU_SPHERE_LANES_H

// The lane helpers (Lanes, lanes_abs, lanes_min, lanes_splat, any_lane) are
// cpu/triangle_lane_ops.h's, which has no include guard and which triangle_lanes.h has
// already included in this namespace (kernel_support.h includes it first).

// sqrt() on every lane, correctly rounded as the scalar sqrt: SSE's and AVX's sqrtps where
// the lanes are floats, else lane by lane (the double-precision test build).
template <class F> [[gnu::always_inline]] inline F lanes_sqrt(F x) {
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
  if constexpr (sizeof(x[0]) == 4 && sizeof(F) == 16) return __builtin_ia32_sqrtps(x);
  if constexpr (sizeof(x[0]) == 4 && sizeof(F) == 32) return __builtin_ia32_sqrtps256(x);
#endif
  for (int k = 0; k < int(sizeof(F) / sizeof(x[0])); k++) x[k] = std::sqrt(x[k]);
  return x;
}

// The nearest hit of `best` and spheres [0, sphere_soa_count): hit_sphere() on every lane.
template <int bytes> [[gnu::always_inline]] inline Hit nearest_sphere_lanes(Ray ray, Hit best) {
  using L = Lanes<bytes>;
  using F = typename L::F;
  using I = typename L::I;
  using Int = typename L::Int;
  const std::size_t n = sphere_soa_count, stride = sphere_soa_stride;
  const float* cx = sphere_soa;
  const float* cy = cx + stride;
  const float* cz = cy + stride;
  const float* radii = cz + stride;
  const float* power_terms = radii + stride;
  const float* lead_abs = power_terms + stride;
  const float* others = lead_abs + stride;
  const float* ax = others + stride;
  const float* ay = ax + stride;
  const float* az = ay + stride;
  const F ox = lanes_splat<F>(ray.origin.x), oy = lanes_splat<F>(ray.origin.y), oz = lanes_splat<F>(ray.origin.z);
  const F dx = lanes_splat<F>(ray.dir.x), dy = lanes_splat<F>(ray.dir.y), dz = lanes_splat<F>(ray.dir.z);
  const F aox = lanes_abs(ox), aoy = lanes_abs(oy), aoz = lanes_abs(oz);
  const F oo = lanes_splat<F>(dot(ray.origin, ray.origin));
  const F zero = F{}, infinity = lanes_splat<F>(kInfinity);
  F near_t = lanes_splat<F>(best.t);
  I near_index = I{} - 1;
  I index;
  static constexpr Int iota[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  __builtin_memcpy(&index, iota, sizeof index);
  for (std::size_t at = 0u; at < n; at += std::size_t(L::count), index += L::count) {
    // The operations of hit_sphere(), in the same order: the same roundings.
    const F r = L::load(radii + at);
    const F fx = ox - L::load(cx + at), fy = oy - L::load(cy + at), fz = oz - L::load(cz + at);
    const F b = -((fx * dx + fy * dy) + fz * dz);
    const F gx = fx + b * dx, gy = fy + b * dy, gz = fz + b * dz;
    const F l = lanes_sqrt((gx * gx + gy * gy) + gz * gz);  // length(f + b * ray.dir)
    const F disc = (r - l) * (r + l);
    I live = ~(disc < zero) & (index < Int(n));
    if (!any_lane(live)) continue;
    const F fl = lanes_sqrt((fx * fx + fy * fy) + fz * fz);  // length(f)
    F c = (fl - r) * (fl + r);
    F c_scale = fl * fl + r * r;
    // sphere_power_from_world_origin(): the sphere's own terms from the arrays.
    const F dot_oc = (ox * L::load(cx + at) + oy * L::load(cy + at)) + oz * L::load(cz + at);
    const F power = (oo + L::load(power_terms + at)) - 2.0f * dot_oc;
    const F dot_abs = (aox * L::load(ax + at) + aoy * L::load(ay + at)) + aoz * L::load(az + at);
    const F scale = ((oo + 2.0f * dot_abs) + L::load(lead_abs + at)) + L::load(others + at);
    const I from_world = scale < c_scale;
    c = from_world ? power : c;
    c_scale = from_world ? scale : c_scale;
    const F h = lanes_sqrt(disc);
    const F q = b + (b >= zero ? h : -h);
    live &= ~(q == zero);
    const F t_small = c / q;
    F t = infinity;
    t = q > kSphereRootError * (fl + r) ? q : t;
    t = t_small > kSphereRootError * c_scale / lanes_abs(q) ? lanes_min(t, t_small) : t;
    const I hit = live & (t < near_t);
    near_t = hit ? t : near_t;
    near_index = hit ? index : near_index;
  }
  // The nearest of the lanes, the lower index of equal distances (the loop's first).
  Int nearest = -1;
  float t_best = best.t;
  for (int k = 0; k < L::count; k++) {
    if (near_index[k] < 0) continue;
    if (nearest < 0 || near_t[k] < t_best || (near_t[k] == t_best && near_index[k] < nearest)) {
      t_best = near_t[k];
      nearest = near_index[k];
    }
  }
  if (nearest < 0) return best;
  return Hit(t_best, 0.0f, 0.0f, uint(nearest), kPrimSphere);
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
[[gnu::target("avx2")]] inline Hit nearest_sphere_avx2(Ray ray, Hit best) {
  return nearest_sphere_lanes<32>(ray, best);
}
#endif

// The CPU's nearest_sphere() (declared in intersect.glsl): the lanes when the spheres are
// also laid out as arrays, else the loop in index order; the same hits.
Hit nearest_sphere(Ray ray, Hit best) {
  if (sphere_soa == nullptr) return nearest_sphere_in_order(ray, best);
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2) return nearest_sphere_avx2(ray, best);
#endif
  return nearest_sphere_lanes<16>(ray, best);
}

#endif  // PT_CPU_SPHERE_LANES_H
