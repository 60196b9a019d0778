// The statistic of pt_compare (common/app/compare.h) on synthetic films whose noise is
// known: two films of one Gaussian noise are consistent about as often as alpha says; a
// shifted mean is found by the mean's t, a bias in one region by that region's z; a rare
// bright outcome that a low-spp film never met does not make it inconsistent with a
// high-spp one (the larger of the two variance estimates); films without a variance, with
// non-finite sums or of another size are refused. Not in the article: tooling.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <vector>

#include "common/app/compare.h"
#include "common/base/error.h"
#include "tests/support/test_render.h"

using namespace pt;
using pt::test::test_seed;

namespace {

// A film of width x height pixels, spp samples each, every sample a grey value drawn by
// `draw(x, y, rng)` (grey: its luminance is the value), one pass per sample.
Film synthetic(int width, int height, int spp, std::uint32_t seed,
               const std::function<double(int, int, std::mt19937_64&)>& draw) {
  Film film(width, height);
  std::mt19937_64 rng(seed);
  std::vector<glm::vec4> pass(std::size_t(width) * std::size_t(height));
  for (int s = 0; s < spp; s++) {
    for (int y = 0; y < height; y++) {
      for (int x = 0; x < width; x++) {
        const float v = float(draw(x, y, rng));
        pass[std::size_t(y) * std::size_t(width) + std::size_t(x)] = glm::vec4(v, v, v, std::fabs(v));
      }
    }
    film.add_pass(pass, 1);
  }
  return film;
}

// Gaussian noise of standard deviation sigma around a mean that varies over the image,
// plus `bias(x, y)`.
Film gaussian(int size, int spp, std::uint32_t seed, double sigma, const std::function<double(int, int)>& bias = {}) {
  return synthetic(size, size, spp, seed, [&](int x, int y, std::mt19937_64& rng) {
    std::normal_distribution<double> normal(0.0, sigma);
    return 1.0 + 0.5 * std::sin(0.3 * x + 0.2 * y) + (bias ? bias(x, y) : 0.0) + normal(rng);
  });
}

int error_code(const std::function<void()>& f, std::string& message) {
  try {
    f();
  } catch (const Error& e) {
    message = e.what();
    return e.code();
  }
  return 0;
}

}  // namespace

TEST_CASE("compare: the two-sided normal threshold and p-value", "[compare]") {
  CHECK(two_sided_threshold(0.05) == Approx(1.959964).epsilon(1e-6));
  CHECK(two_sided_threshold(0.01) == Approx(2.575829).epsilon(1e-6));
  CHECK(two_sided_threshold(0.01 / 17) == Approx(3.43698).epsilon(1e-5));  // 16 regions + the mean at alpha 0.01
  CHECK(two_sided_p(1.959964) == Approx(0.05).epsilon(1e-5));
  CHECK(two_sided_p(-2.575829) == Approx(0.01).epsilon(1e-5));
  CHECK(two_sided_p(two_sided_threshold(1e-9)) == Approx(1e-9).epsilon(1e-6));
}

TEST_CASE("compare: two films of one Gaussian noise are consistent at about the rate alpha says",
          "[compare][statistical]") {
  // 200 pairs at alpha 0.05: Bonferroni's bound says at most 5% false alarms, 10 expected
  // at most; 20 or more would happen with probability below 1e-3 if the bound held.
  const int pairs = 200;
  int alarms = 0;
  double t2 = 0.0;
  CompareSettings settings;
  settings.alpha = 0.05;
  for (int k = 0; k < pairs; k++) {
    Film a = gaussian(32, 16, test_seed(2 * k), 0.8), b = gaussian(32, 16, test_seed(2 * k + 1), 0.8);
    Comparison c = compare_films(a, b, settings);
    alarms += !c.consistent;
    t2 += c.mean_t * c.mean_t;
    CHECK(c.tests == 17);
    CHECK(c.consistent == (c.p_value >= settings.alpha));
  }
  INFO("false alarms " << alarms << " of " << pairs << ", rms t " << std::sqrt(t2 / pairs));
  CHECK(alarms < 20);
  // The image mean's t is close to a standard normal: its RMS over 200 pairs is 1 +- 0.05
  // (the larger of two variance estimates makes it a little below 1).
  CHECK(std::sqrt(t2 / pairs) > 0.8);
  CHECK(std::sqrt(t2 / pairs) < 1.15);
}

TEST_CASE("compare: a shifted mean is found by the mean's t", "[compare][statistical]") {
  // se of the image mean's difference: 0.8 sqrt(2 / (32 x 32 x 16)) = 0.0088; a shift of
  // 0.07 is t = 7.9, over the threshold 3.44 at alpha 0.01 by 4.5 standard deviations.
  Film a = gaussian(32, 16, test_seed(500), 0.8);
  Film b = gaussian(32, 16, test_seed(501), 0.8, [](int, int) { return 0.07; });
  Comparison c = compare_films(a, b, CompareSettings{});
  CHECK(c.mean_t > c.threshold);
  CHECK(c.mean_failed);
  CHECK_FALSE(c.consistent);
  CHECK(c.test_mean - c.ref_mean == Approx(0.07).margin(0.03));
  CHECK(c.p_value < 0.01);
}

TEST_CASE("compare: a bias in one region is found by that region's z, not by the mean", "[compare][statistical]") {
  // +0.25 in the block (16..23, 8..15) of a 64x64 image, sigma 0.8, 16 spp: the block's
  // summed difference is 64 x 0.25 = 16 with a standard deviation of
  // sqrt(64 x 0.64 x (1/16 + 1/16)) = 2.26, z about 7; the mean's t is about
  // 16 / (2.26 x 8) = 0.9; the threshold at alpha 0.01 over 64 regions and the mean is 3.78.
  auto block = [](int x, int y) { return x >= 16 && x < 24 && y >= 8 && y < 16 ? 0.25 : 0.0; };
  Film a = gaussian(64, 16, test_seed(600), 0.8);
  Film b = gaussian(64, 16, test_seed(601), 0.8, block);
  Comparison c = compare_films(a, b, CompareSettings{});
  CHECK(c.threshold == Approx(3.78).margin(0.01));
  CHECK_FALSE(c.consistent);
  CHECK_FALSE(c.mean_failed);
  // The block is region 10 (row 1, column 2 of 8); any other region is over the threshold
  // with probability below 63 x 0.01 / 65, about 1%, so only the block is required.
  CHECK(c.failed_regions >= 1);
  CHECK(c.worst == 10);
  CHECK(std::fabs(c.regions[10].z) > c.threshold);
  const RegionTest& w = c.regions[c.worst];
  CHECK(w.x0 == 16);
  CHECK(w.y0 == 8);
  CHECK(w.x1 == 24);
  CHECK(w.y1 == 16);
  CHECK(w.z > c.threshold);
  CHECK(w.difference == Approx(0.25).margin(0.1));
  // The z-map: values R pixel z, G region z, B 1 in the failed region; the picture outlines it.
  std::vector<float> values = zmap_values(c), picture = zmap_picture(c);
  const std::size_t corner = 3 * (8 * 64 + 16), inside = 3 * (11 * 64 + 19), outside = 0;
  CHECK(values[corner + 1] == Approx(w.z));
  CHECK(values[corner + 2] == 1.0f);
  CHECK(values[outside + 2] == 0.0f);
  CHECK(values[inside] == Approx(c.pixel_z[11 * 64 + 19]));
  CHECK(picture[corner] == 1.0f);
  CHECK(picture[corner + 1] == 1.0f);
  CHECK(picture[corner + 2] == 0.0f);
  CHECK(picture[inside + 1] == 0.0f);  // inside: red or blue, never yellow
}

TEST_CASE("compare: regions follow --region and the image's edges", "[compare]") {
  Film a = gaussian(20, 4, 1, 0.5), b = gaussian(20, 4, 2, 0.5);
  CompareSettings s;
  s.region = 8;
  Comparison c = compare_films(a, b, s);
  REQUIRE(c.regions.size() == 9);  // 8, 8 and 4 pixels across and down
  CHECK(c.regions[2].x0 == 16);
  CHECK(c.regions[2].x1 == 20);
  CHECK(c.regions[8].y1 == 20);
  CHECK(c.tests == 10);
  s.region = 100;
  CHECK(compare_films(a, b, s).regions.size() == 1);
}

TEST_CASE("compare: a rare bright outcome that a low-spp film never met is not a bias", "[compare][statistical]") {
  // Each sample is 100 with probability 0.002, else 0 (mean 0.2). The 16-spp film's 8x8
  // regions hold 1024 samples: about 2 bright ones expected, none in 13% of the regions;
  // such a region's own variance estimate is 0. Against a 1024-spp reference, each
  // film's own variance called about 1 such pair in 3 inconsistent; the larger of the
  // two estimates keeps it at alpha.
  auto rare = [](int, int, std::mt19937_64& rng) {
    return std::uniform_real_distribution<double>()(rng) < 0.002 ? 100.0 : 0.0;
  };
  Film ref = synthetic(16, 16, 1024, test_seed(700), rare);
  int alarms = 0;
  for (int k = 0; k < 40; k++) {
    alarms += !compare_films(ref, synthetic(16, 16, 16, test_seed(701 + k), rare), {}).consistent;
  }
  CHECK(alarms <= 2);
}

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

TEST_CASE("compare: noiseless pixels agree to float rounding and differ beyond it", "[compare]") {
  auto constant = [](double v) { return [v](int, int, std::mt19937_64&) { return v; }; };
  Film a = synthetic(8, 8, 4, 1, constant(0.25));
  Film b = synthetic(8, 8, 4, 2, constant(0.25 * (1.0 + 1e-7)));
  Comparison same = compare_films(a, b, {});
  CHECK(same.consistent);
  CHECK(std::fabs(same.mean_t) < 1.0);
  Film c = synthetic(8, 8, 4, 3, constant(0.26));
  CHECK_FALSE(compare_films(a, c, {}).consistent);
  Film black = synthetic(8, 8, 4, 4, constant(0.0));
  Comparison dark = compare_films(black, black, {});
  CHECK(dark.consistent);
  CHECK(dark.mean_t == 0.0);
}

TEST_CASE("compare: films without a variance, with non-finite sums or of another size are refused", "[compare]") {
  std::string message;
  auto grey = [](int, int, std::mt19937_64& rng) { return std::uniform_real_distribution<double>()(rng); };
  Film a = synthetic(8, 8, 4, 1, grey);
  Film one = synthetic(8, 8, 1, 2, grey);
  CHECK(error_code([&] { compare_films(a, one, {}); }, message) == kExitBadScene);
  CHECK(message.find("the test image holds 1 sample per pixel") != std::string::npos);
  CHECK(message.find("--spp 2 or more") != std::string::npos);
  CHECK(error_code([&] { check_comparable(one, "'ref.exr'", a, "'test.exr'"); }, message) == kExitBadScene);
  CHECK(message.find("'ref.exr' holds 1 sample") != std::string::npos);

  Film wide = synthetic(9, 8, 4, 3, grey);
  CHECK(error_code([&] { check_comparable(a, "'ref.exr'", wide, "'test.exr'"); }, message) == kExitBadScene);
  CHECK(message == "'test.exr' is 9x8 and 'ref.exr' is 8x8: render both at the same --width and --height");

  Film broken = a;
  std::vector<double> sums = broken.sums();
  sums[4 * (2 * 8 + 5)] = std::numeric_limits<double>::infinity();
  broken.restore(broken.spp(), sums);
  CHECK(error_code([&] { compare_films(a, broken, {}); }, message) == kExitBadScene);
  CHECK(message.find("not a finite number, at (5, 2)") != std::string::npos);

  CompareSettings bad;
  bad.alpha = 1.0;
  CHECK(error_code([&] { compare_films(a, a, bad); }, message) == kExitBadOption);
  bad.alpha = 0.01, bad.region = 0;
  CHECK(error_code([&] { compare_films(a, a, bad); }, message) == kExitBadOption);
}
