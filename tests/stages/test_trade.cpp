// The user's trade of time for accuracy (render.h): --target-error stops when the
// estimated per-pixel relative error (Film::per_pixel_relative_error, the figure the
// summary line prints) is reached, and that estimate is honest against closed forms and
// against a long render of the Cornell box: it matches the per-pixel error measured over
// 20 seeds. The image mean's far smaller error
// is honest too. --time-budget stops after the pass that spends it.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "common/scene/analytic_scenes.h"
#include "common/scene/scene_loading.h"
#include "stage3_importance/kernels.h"
#include "stage4_direct_indirect/kernels.h"
#include "tests/support/analytic_suite.h"
#include "tests/support/test_render.h"

using namespace pt;
using namespace pt::test;

namespace {

// The expected image's luminance, pixel by pixel.
std::vector<double> luminances(const ExpectedImage& expected) {
  std::vector<double> l;
  for (const glm::dvec3& c : expected) l.push_back(luminance(c));
  return l;
}

double mean_of(const std::vector<double>& v) {
  double sum = 0.0;
  for (double x : v) sum += x;
  return sum / double(v.size());
}

// The per-pixel relative error a film actually has: the RMS over pixels of (its luminance
// - the closed form's), over the closed form's mean luminance.
double measured_per_pixel_error(const Film& film, const std::vector<double>& expected) {
  double sum = 0.0;
  for (int y = 0; y < film.height(); y++)
    for (int x = 0; x < film.width(); x++) {
      double d = luminance(film.mean(x, y)) - expected[std::size_t(y) * film.width() + x];
      sum += d * d;
    }
  return std::sqrt(sum / (double(film.width()) * film.height())) / mean_of(expected);
}

struct Honesty {
  double printed;   // RMS over the seeds of the printed per-pixel error
  double measured;  // RMS over the seeds of the measured per-pixel error
  double measured_relative_se;  // the standard error of `measured`, relative to it
};

// Renders `runs` seeds and compares the printed per-pixel error with the measured one.
Honesty honesty(const StageKernels& kernels, const Scene& scene, RenderSettings s, const std::vector<double>& expected,
                int runs) {
  double printed2 = 0.0;
  std::vector<double> mse;  // per seed: the measured error squared
  for (int i = 0; i < runs; i++, s.seed++) {
    Film film = render_on_test_backend(kernels, scene, s).film;
    printed2 += std::pow(film.per_pixel_relative_error(), 2);
    mse.push_back(std::pow(measured_per_pixel_error(film, expected), 2));
  }
  double m = mean_of(mse), var = 0.0;
  for (double e : mse) var += (e - m) * (e - m) / (runs - 1.0);
  // The RMSE's relative standard error is half the mean squared error's.
  return {std::sqrt(printed2 / runs), std::sqrt(m), 0.5 * std::sqrt(var / runs) / m};
}

// The printed error within 20% of the measured one (the requirement), and the
// measurement precise enough that 20% is at least 4 (or as the caller says) of its standard errors: a failure is
// a dishonest estimate, not bad luck, and a pass is not a lucky one either.
// That is for independent samples, what the printed figure (the pixel's sample variance
// over N) estimates. Under the default Owen-scrambled Sobol sampler the figure is the
// smaller of two upper bounds, that one and the error from the means of the two halves of
// the samples (Film::track_halves, docs/sampling.md): at least 0.8 of the measured error,
// and at most `most` times it.
void check_honest(const Honesty& h, std::uint32_t sampler, double standard_errors = 4.0, double most = 1.2) {
  INFO("printed " << h.printed << ", measured " << h.measured << " +- " << h.measured_relative_se * h.measured
                  << (sampler == kSamplerSobol ? " (sobol)" : " (independent)"));
  double ratio = h.printed / h.measured;
  CHECK(ratio >= 0.8);
  CHECK(ratio <= (sampler == kSamplerSobol ? most : 1.2));
  CHECK(h.measured_relative_se <= 0.2 / standard_errors);
}

// The furnace box (albedo 0.5): 2 everywhere. With throughput roulette a path's value is
// Le times the number of surfaces it reaches, a geometric number: variance 2 per sample.
Scene furnace() { return analytic::make_furnace({}); }

}  // namespace

// 20 seeds x 256 pixels (64 at 2048 spp) are 5,120 (1,280) squared errors: their mean is
// known to about 3% (6%), the RMSE to half that, so +-20% is 6 or more standard errors.
// (8x8 pixels, not fewer, at 2048 spp: a 6x6 film at 4096 spp made sobol's error 0.72 of
// the printed one, a gain of its points on that film that the halves' figure does not see.)
// Under sobol the furnace's paths of many bounces gain little from the points' cover: the
// halves' figure holds the printed error within 20% there too (measured 0.98 to 1.01).
TEST_CASE("trade: the printed per-pixel error is within 20% of the measured one over 20 seeds, furnace",
          "[stage3][trade][statistical]") {
  const int runs = 20;
  for (std::uint32_t sampler : {kSamplerIndependent, kSamplerSobol}) {
    for (std::uint64_t spp : {16u, 256u, 2048u}) {
      int size = spp >= 2048 ? 8 : 16;
      INFO(spp << " spp, " << size << "x" << size);
      RenderSettings s = settings(size, size, spp, test_seed(5000 + std::uint32_t(spp) + 100 * sampler));
      s.roulette = kRouletteThroughput;
      s.sampler = sampler;
      check_honest(honesty(stage3::kernels(), furnace(), s, std::vector<double>(std::size_t(size) * size, 2.0), runs),
                   sampler);
    }
  }
}

TEST_CASE("trade: the printed per-pixel error is within 20% of the measured one over 20 seeds (under sobol at least "
          "0.8 and at most 6 or 4 times it), floor under a light",
          "[stage4][trade][statistical]") {
  const int runs = 20;
  analytic::FloorLightScene a;
  Scene scene = analytic::make_floor_light(a);
  for (std::uint32_t sampler : {kSamplerIndependent, kSamplerSobol}) {
    for (std::uint64_t spp : {16u, 256u, 2048u}) {
      int size = spp >= 2048 ? 8 : 16;
      INFO(spp << " spp, " << size << "x" << size);
      RenderSettings s = settings(size, size, spp, test_seed(6000 + std::uint32_t(spp) + 100 * sampler));
      s.sampler = sampler;
      // Under sobol at most 6 times the measured error at 16 spp, where the halves of 8
      // points are poor nets and the sample variance's figure stays the smaller (measured
      // 5.0), and 4 times from 256 spp on (measured 1.33, and 1.80 at 2048 spp; 2.63 at the
      // 4096 spp this case had until 2026-12-07; the sample variance's figure alone was 24
      // and 197 times it).
      check_honest(honesty(stage4::kernels(), scene, s, luminances(floor_light_image(a, size)), runs), sampler, 4.0,
                   spp <= 16 ? 6.0 : 4.0);
    }
  }
}

// The Cornell box has no closed form: a long render of the same pixels stands in for it,
// at 32x32 pixels and, averaged 2x2 (a pixel is the union of its four quarters), at 16x16.
// The measured error then holds the reference's own noise too, E[(x - ref)^2] = Var x +
// Var ref per pixel; the reference's film knows its variance, which is taken off.
struct Reference {
  std::vector<double> luminance, variance;  // per pixel: the mean's, and its variance
};

Reference cornell_reference(const Film& film, int size) {
  const int k = film.width() / size;
  Reference r;
  for (int y = 0; y < size; y++) {
    for (int x = 0; x < size; x++) {
      double l = 0.0, v = 0.0;
      for (int j = 0; j < k; j++) {
        for (int i = 0; i < k; i++) {
          l += luminance(film.mean(k * x + i, k * y + j)) / double(k * k);
          v += film.sample_variance(k * x + i, k * y + j) / double(film.spp()) / double(k * k * k * k);
        }
      }
      r.luminance.push_back(l), r.variance.push_back(v);
    }
  }
  return r;
}

TEST_CASE("trade: the printed per-pixel error is within 20% of the measured one over 20 or 40 seeds, Cornell box "
          "against a long reference (independent samples; under sobol at least 0.8 and at most 2 times it)",
          "[stage4][trade][statistical]") {
  Scene scene = make_builtin_scene("cornell");
  RenderSettings r = settings(32, 32, 1u << 14, test_seed(8000));
  r.sampler = kSamplerIndependent;  // so that its sample variance is its error's
  const Film long_render = render_on_test_backend(stage4::kernels(), scene, r).film;
  // Independent samples at 1024 spp only: under sobol the error there is below what an
  // affordable reference resolves (the closed-form cases above test it, to 4096 spp). The
  // third case was 4096 spp until 2026-12-07: 42 million of the test's 75 million samples,
  // in a test that was 60% of lab 4's grading time, for a regime the floor's case covers in
  // closed form.
  for (std::uint64_t spp : {16u, 256u, 1024u}) {
    // The box's pixel errors are heavy-tailed (the light's edge): 20 seeds x 1024 squared
    // errors know the RMSE to 4 to 5.5% (over 20 seed offsets), at 1024 spp 40 seeds x 256
    // (16x16) to about 4.5%, so 20% is at least 3 of their standard errors (check_honest
    // asks the precision for that).
    const int size = spp >= 1024 ? 16 : 32, runs = spp >= 1024 ? 40 : 20;
    const Reference ref = cornell_reference(long_render, size);
    const double mean = mean_of(ref.luminance), noise2 = mean_of(ref.variance) / (mean * mean);
    INFO(spp << " spp, " << size << "x" << size << "; the reference's own relative error " << std::sqrt(noise2));
    RenderSettings s = settings(size, size, spp, test_seed(8100 + std::uint32_t(spp)));
    s.sampler = kSamplerIndependent;
    Honesty h = honesty(stage4::kernels(), scene, s, ref.luminance, runs);
    const double mse = h.measured * h.measured;
    CHECK(noise2 < 0.25 * mse);  // a reference long enough to stand in for the answer
    h.measured_relative_se *= mse / (mse - noise2);
    h.measured = std::sqrt(mse - noise2);
    check_honest(h, kSamplerIndependent, 3.0);
  }
  // The default sampler at 16 and 256 spp, where the reference resolves its error: the
  // smaller of the sample variance's and the halves' figures within 0.8 to 2 times the
  // measured error (measured 1.48 and 1.12). 40 seeds: with 20 the RMSE was known to 6.2%
  // for one of 20 seed offsets.
  for (std::uint64_t spp : {16u, 256u}) {
    const Reference ref = cornell_reference(long_render, 32);
    const double mean = mean_of(ref.luminance), noise2 = mean_of(ref.variance) / (mean * mean);
    INFO(spp << " spp, 32x32, sobol; the reference's own relative error " << std::sqrt(noise2));
    RenderSettings s = settings(32, 32, spp, test_seed(8200 + std::uint32_t(spp)));
    Honesty h = honesty(stage4::kernels(), scene, s, ref.luminance, 40);
    const double mse = h.measured * h.measured;
    CHECK(noise2 < 0.25 * mse);
    h.measured_relative_se *= mse / (mse - noise2);
    h.measured = std::sqrt(mse - noise2);
    check_honest(h, kSamplerSobol, 3.0, 2.0);
  }
}

TEST_CASE("trade: --target-error 0.05 ends with a measured per-pixel error of at most about 0.06",
          "[stage4][trade][statistical]") {
  const int size = 16, runs = 10;
  analytic::FloorLightScene a;
  Scene scene = analytic::make_floor_light(a);
  std::vector<double> expected = luminances(floor_light_image(a, size));
  RenderSettings s = settings(size, size, 0xffffffffu, test_seed(7000));
  s.target_error = 0.05;
  double measured2 = 0.0;
  for (int i = 0; i < runs; i++, s.seed++) {
    Film film = render_on_test_backend(stage4::kernels(), scene, s).film;
    double measured = measured_per_pixel_error(film, expected);
    INFO("seed " << s.seed << ": " << film.spp() << " spp, printed " << film.per_pixel_relative_error()
                 << ", measured " << measured);
    CHECK(film.spp() >= kMinSamplesForError);
    CHECK(film.per_pixel_relative_error() <= 0.05);
    // One run's RMSE over 256 pixels is known to about 5%: 0.06 is 4 of those above 0.05.
    CHECK(measured <= 0.06);
    measured2 += measured * measured;
  }
  CHECK(std::sqrt(measured2 / runs) <= 0.055);
}

TEST_CASE("trade: the estimated error is honest and --target-error 0.02 ends below about 0.03 measured",
          "[stage3][trade][statistical]") {
  analytic::FurnaceScene furnace;
  furnace.albedo = 0.8f;  // answer 5
  Scene scene = analytic::make_furnace(furnace);
  // A correct estimator reaches the target at about 2,000 samples per pixel, its paths ended
  // by the roulette after a few bounces. The caps, four times that and 64 bounces (0.8^64 <
  // 1e-6 of the answer), only bound the time a wrong one takes to fail: an estimator whose
  // weights average above 1 (lab 3's mutant cosine_pdf_uniform) never ends a path by the
  // roulette nor reaches the target, and the first run that misses it ends the test.
  RenderSettings s = settings(4, 4, 4 * 2048, test_seed(3000));
  s.roulette = kRouletteThroughput;
  s.depth_cap = 64;
  s.target_error = 0.02;
  int below = 0, honest = 0;
  const int runs = 20;
  for (int i = 0; i < runs; i++, s.seed++) {
    RenderResult r = render_on_test_backend(stage3::kernels(), scene, s);
    REQUIRE(r.film.per_pixel_relative_error() <= 0.02);
    below += measured_per_pixel_error(r.film, std::vector<double>(16, 5.0)) < 0.03;
    // The image mean's error: a standard error says where the error usually is, within a
    // factor 2 of it, or below it (an error much smaller than its standard error is luck,
    // not dishonesty).
    double estimated = r.film.relative_standard_error();
    double measured = std::abs(r.film.mean_luminance() - 5.0) / 5.0;
    honest += measured <= 2.0 * estimated;
  }
  // The measured per-pixel error over 16 pixels is e sqrt(chi2_16 / 16): below 1.5 e in
  // 99.7% of runs. The image mean's is |N(0, e)|: below 2 e in 95%. Binomial(20, 0.997) is
  // >= 13 with probability 1 - 1e-12; Binomial(20, 0.95) >= 16 with 0.984.
  CHECK(below >= 13);
  CHECK(honest >= 16);
}

TEST_CASE("trade: --time-budget stops after the pass that spends it, with a correct image of its spp",
          "[stage3][trade]") {
  Scene scene = analytic::make_furnace({});
  RenderSettings s = settings(32, 32, 0xffffffffu, 1);
  s.roulette = kRouletteThroughput;
  s.time_budget = 0.2;
  RenderResult r = render_on_test_backend(stage3::kernels(), scene, s);
  CHECK(r.seconds >= 0.2);
  CHECK(r.film.spp() > 0);
  CHECK(r.film.spp() < 0xffffffffu);
}
