// The CPU's fast path through the brute-force triangle loop of intersect.glsl (the article's
// raycasting step, Eq. 2, is this search for the nearest surface). C++ only: a GLSL compiler
// never sees it. The triangles are also kept as a structure of arrays (one array per vertex
// and axis, padded to a multiple of kSoaBlock with empty triangles; pt::TriangleSoa). Blocks
// of kSoaBlock triangles are tested branch-free, which the compiler turns into SIMD code, by
// the same edge functions and scaled distance as hit_triangle(), against the nearest hit
// known at the start of the block. That test only rejects: a triangle it lets through is
// then tested by hit_triangle() itself, in index order. Since the nearest hit only gets
// nearer, everything it rejects hit_triangle() would have rejected too, and the hits found
// are the same, bit for bit, as the loop over hit_triangle() alone (tests/common/
// test_intersect_soa.cpp).
// No include guard of its own: intersect.glsl's guard covers it (a test that compiles the
// kernels twice, as float and as double, undefines that one).

const uint kSoaBlock = 8u;

Hit hit_triangles_blocked(Ray ray, RayShear rs, Hit best) {
  const uint n = params.counts.x;
  const uint stride = triangle_soa_stride;
  // Array (vertex v, axis k) starts at triangle_soa + (3 v + k) stride; the ray's axes
  // are chosen once here, so the block loop below indexes nothing at run time.
  const float* p0x = triangle_soa + (0u + uint(rs.kx)) * stride;
  const float* p0y = triangle_soa + (0u + uint(rs.ky)) * stride;
  const float* p0z = triangle_soa + (0u + uint(rs.kz)) * stride;
  const float* p1x = triangle_soa + (3u + uint(rs.kx)) * stride;
  const float* p1y = triangle_soa + (3u + uint(rs.ky)) * stride;
  const float* p1z = triangle_soa + (3u + uint(rs.kz)) * stride;
  const float* p2x = triangle_soa + (6u + uint(rs.kx)) * stride;
  const float* p2y = triangle_soa + (6u + uint(rs.ky)) * stride;
  const float* p2z = triangle_soa + (6u + uint(rs.kz)) * stride;
  const float ox = ray.origin[rs.kx], oy = ray.origin[rs.ky], oz = ray.origin[rs.kz];
  const float sx = rs.s.x, sy = rs.s.y, sz = rs.s.z;
  for (uint base = 0u; base < n; base += kSoaBlock) {
    const float best_t = best.t;
    int maybe[kSoaBlock];
    for (uint k = 0u; k < kSoaBlock; k++) {
      const uint i = base + k;
      // The operations of hit_triangle(), in the same order: the same roundings.
      const float az0 = p0z[i] - oz, bz0 = p1z[i] - oz, cz0 = p2z[i] - oz;
      const float ax = (p0x[i] - ox) - sx * az0, ay = (p0y[i] - oy) - sy * az0;
      const float bx = (p1x[i] - ox) - sx * bz0, by = (p1y[i] - oy) - sy * bz0;
      const float cx = (p2x[i] - ox) - sx * cz0, cy = (p2y[i] - oy) - sy * cz0;
      const float u = cx * by - cy * bx;
      const float v = ax * cy - ay * cx;
      const float w = bx * ay - by * ax;
      const bool outside = ((u < 0.0f) | (v < 0.0f) | (w < 0.0f)) & ((u > 0.0f) | (v > 0.0f) | (w > 0.0f));
      const float det = u + v + w;
      const float t_scaled = u * (sz * az0) + v * (sz * bz0) + w * (sz * cz0);
      const bool far_neg = (det < 0.0f) & ((t_scaled >= 0.0f) | (t_scaled < best_t * det));
      const bool far_pos = (det > 0.0f) & ((t_scaled <= 0.0f) | (t_scaled > best_t * det));
      maybe[k] = int(!outside & (det != 0.0f) & !far_neg & !far_pos);
    }
    for (uint k = 0u; k < kSoaBlock; k++) {
      if (maybe[k] != 0) best = hit_triangle(ray, rs, base + k, best);
    }
  }
  return best;
}
