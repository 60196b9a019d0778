// The sampler (common/kernel/sampler.glsl), compiled as the CPU kernels compile it: the
// unscrambled Sobol points are the published ones (Joe and Kuo's direction numbers), Owen
// scrambling is nested and keeps every set a (0,m,2)-net, a sample's numbers are uniform and
// independent across dimensions and pixels, and randomised QMC integrates without bias and
// with an error that falls faster than Monte Carlo's N^-1/2 on a smooth integrand. The CPU
// and the GPU giving the same numbers is tests/gpu/test_sampler_agree.cpp.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "cpu/kernel_prelude.h"
#include "tests/support/chi2.h"
#include "tests/support/statistics.h"
#include "tests/support/test_render.h"

namespace {  // internal linkage: each test file compiles its own copy of the kernel code
namespace kernel {
#include "cpu/kernel_begin.h"
#include "common/kernel/sampler.glsl"
}  // namespace kernel
}  // namespace

namespace {

using kernel::uint;

// Sobol's second dimension from Joe and Kuo's parameters for it (d = 2: s = 1, a = 0,
// m_1 = 1), by their general recurrence, independent of the kernel's shortcut:
// v_k = v_{k-s} xor (v_{k-s} >> s) xor (the a-weighted earlier v), as 32-bit fractions.
std::vector<uint> joe_kuo_directions(int s, uint a, const std::vector<uint>& m) {
  std::vector<uint> v(33, 0u);
  for (int k = 1; k <= s; k++) v[k] = m[k - 1] << (32 - k);
  for (int k = s + 1; k <= 32; k++) {
    v[k] = v[k - s] ^ (v[k - s] >> s);
    for (int j = 1; j < s; j++) {
      if ((a >> (s - 1 - j)) & 1u) v[k] ^= v[k - j];
    }
  }
  return v;
}

uint sobol_from_directions(const std::vector<uint>& v, uint i) {
  uint x = 0u;
  for (int k = 1; i != 0u; k++, i >>= 1u) {
    if (i & 1u) x ^= v[k];
  }
  return x;
}

// The point `index` of slot `slot` of the pixel keyed `key`, as the kernel's sample_2d
// returns it.
glm::vec2 point(uint key, uint slot, uint index) {
  glm::uvec2 bits = kernel::sobol_slot_point(key, slot, index);
  return glm::vec2(kernel::unit_float(bits.x), kernel::unit_float(bits.y));
}

// Whether n = 2^m points form a (0,m,2)-net: every elementary box of 2^-a by 2^-(m-a)
// holds exactly one of them.
bool is_02_net(const std::vector<glm::vec2>& points, int m) {
  for (int a = 0; a <= m; a++) {
    std::vector<int> count(std::size_t(1) << m, 0);
    for (glm::vec2 p : points) {
      std::size_t bx = std::size_t(double(p.x) * double(1u << a));
      std::size_t by = std::size_t(double(p.y) * double(1u << (m - a)));
      if (++count[(bx << (m - a)) | by] > 1) return false;
    }
  }
  return true;
}

// The smallest t for which 2^m points in [0,1)^d, given as their leading m bits per
// coordinate, form a (t,m,d)-net: every elementary box of volume 2^(t-m) holds 2^t points
// (equivalently, the 2^(m-t) boxes of each shape are all hit).
int net_t_value(const std::vector<std::vector<uint>>& points, int m, int d) {
  for (int t = 0; t <= m; t++) {
    bool ok = true;
    std::vector<int> shape(d, 0);
    // Every split of m - t bits among the d coordinates.
    std::function<void(int, int)> visit = [&](int axis, int left) {
      if (!ok) return;
      if (axis == d - 1) {
        shape[axis] = left;
        std::vector<char> hit(std::size_t(1) << (m - t), 0);
        for (const auto& p : points) {
          std::size_t box = 0;
          for (int k = 0; k < d; k++) box = (box << shape[k]) | (p[k] >> (m - shape[k]));
          hit[box] = 1;
        }
        for (char h : hit) ok = ok && h;
        return;
      }
      for (int a = 0; a <= left; a++) shape[axis] = a, visit(axis + 1, left - a);
    };
    visit(0, m - t);
    if (ok) return t;
  }
  return m;
}

// The leading m bits of the 2^m points `first` ... of one pixel's block (slots 2b, 2b + 1),
// coordinates `dims` of its four (0, 1 of the even slot, 2, 3 of the odd one).
std::vector<std::vector<uint>> block_bits(uint key, uint block, uint first, int m, const std::vector<int>& dims) {
  std::vector<std::vector<uint>> out;
  for (uint i = 0; i < (1u << m); i++) {
    glm::uvec2 even = kernel::sobol_slot_point(key, 2 * block, first + i);
    glm::uvec2 odd = kernel::sobol_slot_point(key, 2 * block + 1, first + i);
    uint all[4] = {even.x, even.y, odd.x, odd.y};
    std::vector<uint> p;
    for (int d : dims) p.push_back(m == 0 ? 0u : all[d] >> (32 - m));
    out.push_back(p);
  }
  return out;
}

// The same of the unscrambled Sobol points 0 ... 2^m - 1, dimensions `dims`.
std::vector<std::vector<uint>> sobol_bits(int m, const std::vector<int>& dims) {
  std::vector<std::vector<uint>> out;
  for (uint i = 0; i < (1u << m); i++) {
    uint all[4] = {kernel::sobol_dimension0(i), kernel::sobol_dimension1(i), kernel::sobol_dimension2(i),
                   kernel::sobol_dimension3(i)};
    std::vector<uint> p;
    for (int d : dims) p.push_back(m == 0 ? 0u : all[d] >> (32 - m));
    out.push_back(p);
  }
  return out;
}

}  // namespace

TEST_CASE("sampler: the unscrambled Sobol points are the published ones", "[sampler]") {
  // Joe and Kuo, "Notes on generating Sobol' sequences" (2008), the first points of
  // dimensions 1 to 4 in Gray-code order (point n is x_{n xor (n >> 1)}).
  const double dim1[] = {0, 0.5, 0.75, 0.25, 0.375, 0.875, 0.625, 0.125, 0.1875, 0.6875, 0.9375, 0.4375};
  const double dim2[] = {0, 0.5, 0.25, 0.75, 0.375, 0.875, 0.125, 0.625, 0.3125, 0.8125, 0.0625, 0.5625};
  const double dim3[] = {0, 0.5, 0.25, 0.75, 0.625, 0.125, 0.875, 0.375, 0.9375, 0.4375, 0.6875, 0.1875};
  const double dim4[] = {0, 0.5, 0.25, 0.75, 0.875, 0.375, 0.625, 0.125, 0.4375, 0.9375, 0.1875, 0.6875};
  for (uint n = 0; n < 12; n++) {
    uint g = n ^ (n >> 1u);
    INFO("point " << n);
    CHECK(double(kernel::sobol_dimension0(g)) / 4294967296.0 == dim1[n]);
    CHECK(double(kernel::sobol_dimension1(g)) / 4294967296.0 == dim2[n]);
    CHECK(double(kernel::sobol_dimension2(g)) / 4294967296.0 == dim3[n]);
    CHECK(double(kernel::sobol_dimension3(g)) / 4294967296.0 == dim4[n]);
  }
  // Every point, from Joe and Kuo's parameters by the general recurrence; dimension 1 is
  // the identity matrix (s = 0 in their table: the van der Corput sequence).
  // Their rows: d = 2: s = 1, a = 0, m = 1; d = 3: s = 2, a = 1, m = 1 3; d = 4: s = 3, a = 1, m = 1 3 1.
  std::vector<uint> v = joe_kuo_directions(1, 0u, {1u});
  std::vector<uint> v3 = joe_kuo_directions(2, 1u, {1u, 3u});
  std::vector<uint> v4 = joe_kuo_directions(3, 1u, {1u, 3u, 1u});
  std::vector<uint> identity(33, 0u);
  for (int k = 1; k <= 32; k++) identity[k] = 1u << (32 - k);
  for (uint i = 0; i < (1u << 16); i++) {
    REQUIRE(kernel::sobol_dimension1(i) == sobol_from_directions(v, i));
    REQUIRE(kernel::sobol_dimension0(i) == sobol_from_directions(identity, i));
    REQUIRE(kernel::sobol_dimension2(i) == sobol_from_directions(v3, i));
    REQUIRE(kernel::sobol_dimension3(i) == sobol_from_directions(v4, i));
  }
  for (uint i : {0xffffffffu, 0x80000000u, 0x12345678u, 0xdeadbeefu}) {
    CHECK(kernel::sobol_dimension1(i) == sobol_from_directions(v, i));
    CHECK(kernel::sobol_dimension2(i) == sobol_from_directions(v3, i));
    CHECK(kernel::sobol_dimension3(i) == sobol_from_directions(v4, i));
  }
}

TEST_CASE("sampler: Owen scrambling is nested: two fractions that share k leading bits share exactly k after it",
          "[sampler]") {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 20000; trial++) {
    uint seed = rng(), x = rng();
    int k = int(rng() % 32u);
    uint y = x ^ (0x80000000u >> k);           // differ first at bit k from the top
    y ^= (rng() & ((0x80000000u >> k) - 1u));  // and anywhere below it
    uint sx = kernel::owen_scramble(x, seed), sy = kernel::owen_scramble(y, seed);
    uint diff = sx ^ sy;
    INFO("x " << x << ", y " << y << ", seed " << seed << ", k " << k);
    REQUIRE(diff != 0u);
    REQUIRE(__builtin_clz(diff) == k);
  }
}

TEST_CASE("sampler: each pixel's even slots are (0,m,2)-nets in every aligned block of 2^m samples", "[sampler]") {
  std::mt19937 rng(12);
  for (int m = 0; m <= 12; m++) {
    for (int set = 0; set < 6; set++) {
      uint key = rng();
      for (uint slot : {0u, 2u, 6u}) {
        for (uint block : {0u, 1u, 5u, 30u}) {
          std::vector<glm::vec2> pts;
          for (uint i = 0; i < (1u << m); i++) pts.push_back(point(key, slot, block * (1u << m) + i));
          INFO("m " << m << ", key " << key << ", slot " << slot << ", samples from " << block * (1u << m));
          REQUIRE(is_02_net(pts, m));
        }
      }
    }
  }
  // The control: independent points are not nets (the test can fail).
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  std::vector<glm::vec2> random_points;
  for (int i = 0; i < 256; i++) random_points.push_back(glm::vec2(u01(rng), u01(rng)));
  CHECK_FALSE(is_02_net(random_points, 8));
}

TEST_CASE("sampler: a block's odd slot and its four numbers together are nets as good as Sobol's own", "[sampler]") {
  // Owen scrambling keeps a (t,m,s)-net a (t,m,s)-net: the scrambled points of dimensions
  // 2-3 (the odd slot) and 0-3 (the whole block) have the t of the unscrambled Sobol points
  // 0 ... 2^m - 1 (measured: t <= 2 in 2-D, t <= 3 in 4-D for m <= 10), in every aligned
  // block of samples; and the 4-D t is far below that of independent points.
  std::mt19937 rng(13);
  for (int m = 1; m <= 9; m++) {
    int t2 = net_t_value(sobol_bits(m, {2, 3}), m, 2), t4 = net_t_value(sobol_bits(m, {0, 1, 2, 3}), m, 4);
    CHECK(t2 <= 2);
    CHECK(t4 <= 3);
    for (int set = 0; set < 3; set++) {
      uint key = rng();
      for (uint block : {0u, 3u}) {
        uint first = block * (1u << m);
        INFO("m " << m << ", key " << key << ", samples from " << first << ": Sobol's t " << t2 << " (2-D), " << t4
                  << " (4-D)");
        CHECK(net_t_value(block_bits(key, block, first, m, {2, 3}), m, 2) == t2);
        CHECK(net_t_value(block_bits(key, block, first, m, {0, 1, 2, 3}), m, 4) == t4);
      }
    }
  }
  // The control: independent points in 4-D are worse nets than Sobol's (the test can fail).
  for (int m : {6, 8}) {
    std::vector<std::vector<uint>> random_points;
    for (int i = 0; i < (1 << m); i++) {
      random_points.push_back({uint(rng() >> (32 - m)), uint(rng() >> (32 - m)), uint(rng() >> (32 - m)), uint(rng() >> (32 - m))});
    }
    CHECK(net_t_value(random_points, m, 4) > net_t_value(sobol_bits(m, {0, 1, 2, 3}), m, 4));
  }
}

TEST_CASE("sampler: across pixels a sample's numbers are uniform and its dimensions independent",
          "[sampler][statistical]") {
  // For one sample index, the pixels' numbers in dimensions 0-5 (1-D and 2-D requests mixed
  // as a path makes them) binned 8 x 8 per pair of consecutive requests: chi-square against
  // the uniform, Šidák-corrected over the pairs and sample indices at alpha 1e-3.
  const uint pixels = 1u << 14;
  const int bins = 8;
  const std::uint32_t seed = pt::test::test_seed(8100);
  const std::vector<uint> indices = {0u, 1u, 3u, 64u, 1000u};
  const int pairs = 5;
  const double alpha = pt::test::sidak_alpha(1e-3, double(indices.size() * pairs));
  for (uint sample : indices) {
    std::vector<std::vector<int>> counts(pairs, std::vector<int>(bins * bins, 0));
    for (uint p = 0; p < pixels; p++) {
      kernel::start_sample(p, sample, seed, pt::kSamplerSobol);
      float u[6];
      glm::vec2 a = kernel::sample_2d();  // the pixel position
      u[0] = a.x, u[1] = a.y;
      u[2] = kernel::sample_1d();  // e.g. a lobe choice
      u[3] = kernel::sample_1d();  // e.g. a light pick
      glm::vec2 b = kernel::sample_2d();  // e.g. a point on the light
      u[4] = b.x, u[5] = b.y;
      for (int k = 0; k < pairs; k++) counts[k][int(u[k] * bins) * bins + int(u[k + 1] * bins)]++;
    }
    for (int k = 0; k < pairs; k++) {
      double expected = double(pixels) / (bins * bins), chi2 = 0.0;
      for (int c : counts[k]) chi2 += (c - expected) * (c - expected) / expected;
      double p = pt::test::chi2_upper_tail(chi2, bins * bins - 1);
      INFO("sample " << sample << ", numbers " << k << " and " << k + 1 << ": chi2 " << chi2 << ", p " << p);
      CHECK(p > alpha);
    }
  }
}

namespace {

// One pixel's estimate of the integral of f over [0,1)^2 with n samples of dimension 1
// (after the pixel position, as an integrator reads it).
template <class F>
double estimate(F f, uint pixel, uint n, std::uint32_t seed, uint kind) {
  double sum = 0.0;
  for (uint s = 0; s < n; s++) {
    kernel::start_sample(pixel, s, seed, kind);
    kernel::sample_2d();  // dimension 0: the pixel position
    glm::vec2 u = kernel::sample_2d();
    sum += f(double(u.x), double(u.y));
  }
  return sum / n;
}

struct ErrorStats {
  double mean_error = 0.0;  // mean over pixels of (estimate - answer)
  double se = 0.0;          // its standard error
  double rmse = 0.0;        // RMS over pixels of (estimate - answer)
};

template <class F>
ErrorStats errors(F f, double answer, uint n, uint pixels, std::uint32_t seed, uint kind) {
  std::vector<double> e;
  for (uint p = 0; p < pixels; p++) e.push_back(estimate(f, p, n, seed, kind) - answer);
  ErrorStats r;
  for (double v : e) r.mean_error += v / pixels, r.rmse += v * v / pixels;
  double var = 0.0;
  for (double v : e) var += (v - r.mean_error) * (v - r.mean_error) / (pixels - 1);
  r.se = std::sqrt(var / pixels);
  r.rmse = std::sqrt(r.rmse);
  return r;
}


}  // namespace

TEST_CASE("sampler: randomised QMC is unbiased, also for a discontinuous integrand and counts not a power of two",
          "[sampler][statistical]") {
  // The triangle u + v < 0.7 (area 0.245) and a smooth function: each pixel is an
  // independent randomisation, so the mean error over 512 pixels is within z standard
  // errors of 0 (z Šidák-corrected over the 2 x 4 checks at alpha 1e-3).
  auto triangle = [](double u, double v) { return u + v < 0.7 ? 1.0 : 0.0; };
  auto smooth = [](double u, double v) { return std::exp(u) * std::cos(v); };
  const double smooth_answer = (std::exp(1.0) - 1.0) * std::sin(1.0);
  const double z = pt::test::normal_two_sided_quantile(pt::test::sidak_alpha(1e-3, 8.0));
  std::uint32_t seed = pt::test::test_seed(8200);
  for (uint n : {1u, 13u, 64u, 100u}) {
    ErrorStats t = errors(triangle, 0.245, n, 512, seed++, pt::kSamplerSobol);
    ErrorStats s = errors(smooth, smooth_answer, n, 512, seed++, pt::kSamplerSobol);
    INFO(n << " samples: triangle error " << t.mean_error << " +- " << t.se << ", smooth " << s.mean_error << " +- "
           << s.se);
    CHECK(std::abs(t.mean_error) < z * t.se + 1e-12);
    CHECK(std::abs(s.mean_error) < z * s.se + 1e-12);
  }
}

TEST_CASE("sampler: on a smooth integrand the error falls as N^-1.4 (measured -1.36, 20 seeds -1.33..-1.40), N^-0.5 with independent numbers",
          "[sampler][statistical]") {
  // Owen-scrambled (t,m,2)-nets integrate a smooth function with RMSE O(N^-1.5 (log N)^..)
  // (Owen 1997); independent numbers O(N^-1/2). The integrand reads slot 1, after the pixel
  // position, as an integrator's first request does: an odd slot, Sobol's dimensions 2
  // and 3, t <= 2, so the measured slope is a little above -1.5. The slopes of log RMSE over log N from 16 to
  // 1024 samples, RMSE over 256 independent pixels: their relative standard error is
  // about 1/sqrt(2 x 256) = 4%, so the fitted slope is within +-0.05 of the truth.
  auto smooth = [](double u, double v) { return std::exp(u) * std::cos(v); };
  const double answer = (std::exp(1.0) - 1.0) * std::sin(1.0);
  std::vector<double> ns, sobol, independent;
  std::uint32_t seed = pt::test::test_seed(8300);
  for (uint n : {16u, 64u, 256u, 1024u}) {
    ns.push_back(n);
    sobol.push_back(errors(smooth, answer, n, 256, seed++, pt::kSamplerSobol).rmse);
    independent.push_back(errors(smooth, answer, n, 256, seed++, pt::kSamplerIndependent).rmse);
  }
  double qmc = pt::test::log_slope(ns, sobol), mc = pt::test::log_slope(ns, independent);
  INFO("slopes: sobol " << qmc << ", independent " << mc);
  CHECK(qmc < -1.2);
  CHECK(qmc > -1.6);
  CHECK(mc > -0.6);
  CHECK(mc < -0.4);
}
