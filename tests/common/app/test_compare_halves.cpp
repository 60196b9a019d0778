// pt_compare's use of the halves (common/app/compare.h): the halves' upper confidence bound,
// and on synthetic films that know their halves, false alarms kept at alpha, a pixel that
// holds most of its region's error kept out, and a bias hidden under the samples' variance
// found. Not in the article: tooling.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "common/app/compare.h"
#include "tests/support/test_render.h"

using namespace pt;
using pt::test::test_seed;

TEST_CASE("compare: the halves' upper confidence bound", "[compare]") {
  // The bound is sum x nu / q, q the chi-square quantile at 1% of nu = sum^2 / sum_of_squares
  // degrees of freedom, by Wilson and Hilferty: nu (1 - c - 2.326 sqrt(c))^3, c = 2 / (9 nu).
  auto expected = [](double sum, double nu) {
    const double c = 2.0 / (9.0 * nu), root = 1.0 - c - kHalvesBoundZ * std::sqrt(c);
    return sum / (root * root * root);
  };
  CHECK(halves_upper_bound(64.0, 64.0) == Approx(expected(64.0, 64.0)));
  CHECK(halves_upper_bound(64.0, 64.0) == Approx(100.8).epsilon(0.01));  // chi-square(64)'s 1% quantile: 40.6
  CHECK(halves_upper_bound(6.0, 12.0) == Approx(expected(6.0, 3.0)));
  CHECK(std::isinf(halves_upper_bound(0.0, 0.0)));  // halves that agree exactly: no bound
  CHECK(std::isinf(halves_upper_bound(1.0, 1.0)));  // one degree of freedom: no bound
  CHECK(std::isinf(halves_upper_bound(50.0, 2500.0)));  // one term carrying all of the sum
  // Below the true variance far less than 1% of the time for alike terms (their degrees of
  // freedom estimated at about a third of the 64 they have: the bound is cautious): 20000
  // draws of 64 terms of one degree of freedom each; 1% would be 200. (A term that carries
  // most of the variance is compare_films' to refuse: the next tests.)
  std::mt19937_64 rng(test_seed(800));
  std::normal_distribution<double> normal;
  int below = 0;
  double ratio = 0.0;
  for (int k = 0; k < 20000; k++) {
    double sum = 0.0, sq = 0.0;
    for (int i = 0; i < 64; i++) {
      const double d2 = std::pow(normal(rng), 2);
      sum += d2, sq += d2 * d2;
    }
    const double bound = halves_upper_bound(sum, sq);
    below += bound < 64.0;
    ratio += bound / 64.0 / 20000.0;
  }
  INFO(below << " of 20000 bounds below the truth; mean bound / truth " << ratio);
  CHECK(below < 200);
  CHECK(ratio < 3.0);  // about 2.4: cautious, not useless
}

namespace {

// A film that knows its halves (Film::track_halves) from samples m(x, y) + e, where each
// pixel's samples alternate +a and -a about it and e is Gaussian noise of deviation sigma:
// every half of a power-of-two count holds as many +a as -a, so the halves' estimate of
// the error is that of sigma alone, exact in expectation, while the samples' variance,
// a^2 + sigma^2, overstates it as randomised QMC's does.
// hot: the pixels at (3, 5) of every 8x8 block instead take no alternating part and noise of
// deviation `hot`: most of their region's error, and of its sample variance.
Film alternating(int size, int spp, std::uint32_t seed, double a, double sigma, double shift = 0.0, double hot = 0.0) {
  Film film(size, size);
  film.track_halves(0);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, sigma);
  std::vector<glm::vec4> pass(std::size_t(size) * std::size_t(size));
  for (int s = 0; s < spp; s++) {
    for (int y = 0; y < size; y++) {
      for (int x = 0; x < size; x++) {
        const bool is_hot = hot > 0.0 && x % 8 == 3 && y % 8 == 5;
        const double part = is_hot ? hot * normal(rng) / sigma : (s % 2 ? a : -a) + normal(rng);
        const float v = float(1.0 + 0.5 * std::sin(0.3 * x + 0.2 * y) + shift + part);
        pass[std::size_t(y) * std::size_t(size) + std::size_t(x)] = glm::vec4(v, v, v, std::fabs(v));
      }
    }
    film.add_pass(pass, 1);
  }
  return film;
}

}  // namespace

TEST_CASE("compare: where both films know their halves, the halves' bound keeps false alarms at the rate alpha says",
          "[compare][statistical]") {
  // The samples' variance overstates the error 26 times (a = 0.5, sigma = 0.1): the halves
  // decide every region, and only their confidence bound stands between the test and false
  // alarms. 200 pairs at alpha 0.05: at most 5% expected, 20 or more below 1e-3 if it holds.
  const int pairs = 200;
  int alarms = 0, regions = 0;
  double t2 = 0.0;
  CompareSettings settings;
  settings.alpha = 0.05;
  for (int k = 0; k < pairs; k++) {
    Film a = alternating(32, 16, test_seed(900 + 2 * k), 0.5, 0.1);
    Film b = alternating(32, 16, test_seed(901 + 2 * k), 0.5, 0.1);
    REQUIRE(a.has_halves());
    Comparison c = compare_films(a, b, settings);
    alarms += !c.consistent;
    regions += c.halves_regions;
    t2 += c.mean_t * c.mean_t;
  }
  INFO("false alarms " << alarms << " of " << pairs << ", rms t " << std::sqrt(t2 / pairs) << ", regions by the halves "
                       << regions << " of " << 16 * pairs);
  CHECK(regions == 16 * pairs);
  CHECK(alarms < 20);
  // The mean's bound, over 1024 pixels, is about 1.2 times the halves' variance: RMS t about
  // 0.9, give or take 0.05 over 200 pairs (20 seed offsets: 0.79 to 1.00).
  CHECK(std::sqrt(t2 / pairs) > 0.7);
  CHECK(std::sqrt(t2 / pairs) < 1.1);
}

TEST_CASE("compare: a pixel that holds most of its region's error keeps the halves out of that region",
          "[compare][statistical]") {
  // One pixel in 64 with noise 3 (a variance of its mean of 0.56 at 16 spp, against 6e-4 for
  // each of the others, whose samples alternate as above): its one degree of freedom in the
  // halves would, drawn small, hide 93% of the region's error. It holds 35% of the region's
  // sample variance, over kHalvesLargestShare, so no region takes the halves, and false
  // alarms stay at the rate alpha says (200 pairs at alpha 0.05, as above). Without that
  // rule 153 regions took the halves and 8 pairs were called inconsistent.
  const int pairs = 200;
  int alarms = 0, regions = 0, means = 0;
  CompareSettings settings;
  settings.alpha = 0.05;
  for (int k = 0; k < pairs; k++) {
    Film a = alternating(32, 16, test_seed(1500 + 2 * k), 0.5, 0.1, 0.0, 3.0);
    Film b = alternating(32, 16, test_seed(1501 + 2 * k), 0.5, 0.1, 0.0, 3.0);
    Comparison c = compare_films(a, b, settings);
    alarms += !c.consistent;
    regions += c.halves_regions;
    means += c.mean_from_halves;
  }
  INFO("false alarms " << alarms << " of " << pairs << ", regions by the halves " << regions << ", means " << means);
  CHECK(regions == 0);
  CHECK(alarms < 20);
  // (Over the whole image each hot pixel holds 2% of the sample variance, so the mean may take
  // the halves; their bound, with the 16 hot pixels' few degrees of freedom, is mostly above
  // the sample variance's figure, which overstates by 2.6 times only.)
}

TEST_CASE("compare: a bias hidden under the samples' variance is found through the halves", "[compare][statistical]") {
  // a = 1, sigma = 0.1, 16 spp, 32x32: the image mean's standard error is 0.011 from the
  // samples' variance (1.01 / 16 a pixel, two films) and about 0.0017 from the halves' bound
  // (2.4 x 0.01 / 16); a shift of 0.012 is t = 1.1 and t = 7, each give or take 0.1 and 0.65
  // (the true noise, 0.0011): under and over the threshold 3.44 by far.
  Film a = alternating(32, 16, test_seed(1300), 1.0, 0.1);
  Film b = alternating(32, 16, test_seed(1301), 1.0, 0.1, 0.012);
  Comparison with = compare_films(a, b, CompareSettings{});
  INFO("t with the halves " << with.mean_t);
  CHECK(with.halves_regions == 16);
  CHECK(with.mean_from_halves);
  CHECK_FALSE(with.consistent);
  CHECK(with.mean_failed);
  // The same samples in films that do not know their halves: the sample variance's figure.
  Film a2 = alternating(32, 16, test_seed(1300), 1.0, 0.1), b2 = alternating(32, 16, test_seed(1301), 1.0, 0.1, 0.012);
  a2.restore(a2.spp(), a2.sums()), b2.restore(b2.spp(), b2.sums());  // restore() forgets the halves
  REQUIRE_FALSE(a2.has_halves());
  Comparison without = compare_films(a2, b2, CompareSettings{});
  INFO("t without " << without.mean_t);
  CHECK(without.halves_regions == 0);
  CHECK_FALSE(without.mean_from_halves);
  CHECK(without.consistent);
  CHECK(with.test_mean - with.ref_mean == Approx(without.test_mean - without.ref_mean));
}
