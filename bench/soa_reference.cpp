// The structure-of-arrays reference loop of the speed section (soa_reference.h), built at
// -O3: the inner loop over triangles has no branch and no dependence between iterations,
// so the compiler runs it on SIMD lanes; a scalar pass then picks the nearest. Compiled
// twice: for the default x86-64 target (SSE2) and for AVX2.
#include "bench/soa_reference.h"

#include <vector>

namespace pt::bench {

void SoaTriangles::add(glm::vec3 p0, glm::vec3 p1, glm::vec3 p2) {
  glm::vec3 e1 = p1 - p0, e2 = p2 - p0;
  v0x.push_back(p0.x), v0y.push_back(p0.y), v0z.push_back(p0.z);
  e1x.push_back(e1.x), e1y.push_back(e1.y), e1z.push_back(e1.z);
  e2x.push_back(e2.x), e2y.push_back(e2.y), e2z.push_back(e2.z);
}

namespace {

// The loop itself, inlined into each of the two functions below.
[[gnu::always_inline]] inline double closest_hits(const SoaTriangles& tris, const glm::vec3* o, const glm::vec3* d,
                                                  std::size_t count) {
  const std::size_t n = tris.size();
  std::vector<float> t(n);
  float* __restrict tt = t.data();
  const float *v0x = tris.v0x.data(), *v0y = tris.v0y.data(), *v0z = tris.v0z.data();
  const float *e1x = tris.e1x.data(), *e1y = tris.e1y.data(), *e1z = tris.e1z.data();
  const float *e2x = tris.e2x.data(), *e2y = tris.e2y.data(), *e2z = tris.e2z.data();
  double sum = 0.0;
  for (std::size_t r = 0; r < count; r++) {
    const float ox = o[r].x, oy = o[r].y, oz = o[r].z, dx = d[r].x, dy = d[r].y, dz = d[r].z;
    for (std::size_t i = 0; i < n; i++) {
      float px = dy * e2z[i] - dz * e2y[i], py = dz * e2x[i] - dx * e2z[i], pz = dx * e2y[i] - dy * e2x[i];
      float det = e1x[i] * px + e1y[i] * py + e1z[i] * pz;
      float inv = 1.0f / det;
      float sx = ox - v0x[i], sy = oy - v0y[i], sz = oz - v0z[i];
      float u = (sx * px + sy * py + sz * pz) * inv;
      float qx = sy * e1z[i] - sz * e1y[i], qy = sz * e1x[i] - sx * e1z[i], qz = sx * e1y[i] - sy * e1x[i];
      float v = (dx * qx + dy * qy + dz * qz) * inv;
      float dist = (e2x[i] * qx + e2y[i] * qy + e2z[i] * qz) * inv;
      bool hit = (u >= 0.0f) & (v >= 0.0f) & (u + v <= 1.0f) & (dist > 1e-4f);  // no branch: &, not &&
      tt[i] = hit ? dist : 3.4e38f;
    }
    float best = 3.4e38f;
    for (std::size_t i = 0; i < n; i++) best = tt[i] < best ? tt[i] : best;
    sum += best < 3.4e38f ? best : 0.0f;
  }
  return sum;
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target("avx2"))) double closest_hits_avx2(const SoaTriangles& tris, const glm::vec3* o,
                                                         const glm::vec3* d, std::size_t count) {
  return closest_hits(tris, o, d, count);
}
#endif

}  // namespace

double soa_closest_hits(const SoaTriangles& tris, const glm::vec3* o, const glm::vec3* d, std::size_t count, bool avx2) {
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
  if (avx2 && __builtin_cpu_supports("avx2")) return closest_hits_avx2(tris, o, d, count);
#endif
  (void)avx2;
  return closest_hits(tris, o, d, count);
}

}  // namespace pt::bench
