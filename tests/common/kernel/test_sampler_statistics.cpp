// The sampler (common/kernel/sampler.glsl; docs/sampling.md, "What it buys"), compiled as
// the CPU kernels compile it: a sample's numbers are uniform and independent across
// dimensions and pixels, and randomised QMC integrates without bias and with an error that
// falls faster than Monte Carlo's N^-1/2 on a smooth integrand. The nets behind it:
// test_sampler_nets.cpp.
#include <catch2/catch.hpp>

#include <cmath>
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

using kernel::uint;

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
