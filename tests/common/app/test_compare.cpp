// The statistic of pt_compare (common/app/compare.h) on synthetic films whose noise is
// known: two films of one Gaussian noise are consistent about as often as alpha says; a
// shifted mean is found by the mean's t, a bias in one region by that region's z; a rare
// bright outcome that a low-spp film never met does not make it inconsistent with a
// high-spp one (the larger of the two variance estimates); films without a variance, with
// non-finite sums or of another size are refused. The halves: test_compare_halves.cpp.
// Not in the article: tooling.
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
