// The film, the pass schedule, PNG encoding and option parsing: the machinery around the
// integrators (common/render/film.h, render.h, image_output.h, options.h).
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <vector>

#include "common/base/error.h"
#include "common/render/film.h"
#include "common/app/image_output.h"
#include "common/app/options.h"
#include "common/render/render.h"

using namespace pt;

TEST_CASE("film: 2^24 samples of a constant add up to that constant", "[film][stability]") {
  Film film(1, 1);
  const float value = 0.1f;  // not a power of two: float sums of it drift
  const std::uint64_t per_pass = 16;
  std::vector<glm::vec4> pass = {glm::vec4(glm::vec3(value * per_pass), 0.0f)};
  for (std::uint64_t i = 0; i < (std::uint64_t(1) << 24) / per_pass; i++) film.add_pass(pass, per_pass);
  REQUIRE(film.spp() == (std::uint64_t(1) << 24));
  double mean = film.mean(0, 0).x;
  CHECK(std::abs(mean - double(value * per_pass) / per_pass) / value < 1e-6);
  // The failure this guards against: the same sum kept in float.
  float naive = 0.0f;
  for (std::uint64_t i = 0; i < (std::uint64_t(1) << 24); i++) naive += value;
  CHECK(std::abs(double(naive) / double(1 << 24) - value) / value > 1e-2);
}

TEST_CASE("film: variance and relative standard error follow the samples", "[film]") {
  Film film(2, 1);
  // Pixel 0 sees luminance 0 and 2 alternately; pixel 1 a constant 1 (white light).
  for (int i = 0; i < 100; i++) {
    float v = (i % 2) ? 2.0f : 0.0f;
    std::vector<glm::vec4> pass = {glm::vec4(v, v, v, v), glm::vec4(1.0f, 1.0f, 1.0f, 1.0f)};  // w: sqrt(sum lum^2)
    film.add_pass(pass, 1);
  }
  CHECK(film.mean(0, 0).x == Approx(1.0));
  CHECK(film.sample_variance(0, 0) == Approx(100.0 / 99.0));
  CHECK(film.sample_variance(1, 0) == Approx(0.0).margin(1e-12));
  // Image mean 1; its variance (1/4)(100/99)/100.
  CHECK(film.relative_standard_error() == Approx(std::sqrt(0.25 * (100.0 / 99.0) / 100.0)));
}

TEST_CASE("film: the per-pixel relative error is the RMS of the pixels' standard errors over the image mean",
          "[film]") {
  // Hand-made sums. Pixel 0: n samples of luminance 0 and 4 alternately (mean 2, sample
  // variance 4n/(n-1)); pixel 1: a constant 2 (white, variance 0). Image mean 2.
  const std::uint64_t n = 64;
  Film film(2, 1);
  std::vector<double> sums = {2.0 * n, 2.0 * n, 2.0 * n, 16.0 * (n / 2),  // sum of lum^2: (n/2) x 4^2
                              2.0 * n, 2.0 * n, 2.0 * n, 4.0 * n};
  film.restore(n, sums);
  double var0 = 4.0 * n / (n - 1.0);
  CHECK(film.sample_variance(0, 0) == Approx(var0));
  CHECK(film.pixel_standard_error(0, 0) == Approx(std::sqrt(var0 / n)));
  CHECK(film.pixel_standard_error(1, 0) == Approx(0.0).margin(1e-12));
  // RMS over the 2 pixels of (sqrt(var0/n), 0), over the mean 2.
  CHECK(film.per_pixel_relative_error() == Approx(std::sqrt(0.5 * var0 / n) / 2.0));
  // The image mean's error is sqrt(pixels) = sqrt(2) times smaller here.
  CHECK(film.relative_standard_error() == Approx(film.per_pixel_relative_error() / std::sqrt(2.0)));

  // Colour: the variance is of the luminance (Rec. 709), and so is the mean it is divided by.
  Film red(1, 1);
  red.restore(4, {4.0, 0.0, 0.0, 0.2126 * 0.2126 * 8.0});  // samples 0, 2, 0, 2 of pure red: lum 0 or 0.4252
  double lum_var = 0.2126 * 0.2126 * (8.0 - 4.0 * 4.0 / 4.0) / 3.0;
  CHECK(red.per_pixel_relative_error() == Approx(std::sqrt(lum_var / 4.0) / 0.2126));
}

TEST_CASE("film: the per-pixel error is 0 when unknown or for a black image, and never a false 0", "[film]") {
  Film none(3, 2);
  CHECK(none.per_pixel_relative_error() == 0.0);  // 0 spp
  none.restore(1, std::vector<double>(24, 1.0));
  CHECK(none.per_pixel_relative_error() == 0.0);  // 1 spp: no variance yet
  Film black(3, 2);
  black.restore(16, std::vector<double>(24, 0.0));
  CHECK(black.per_pixel_relative_error() == 0.0);  // mean 0: nothing to be relatively wrong about
  CHECK(std::isfinite(black.relative_standard_error()));
  // Sums that are not finite: infinity, so that --target-error never stops on them.
  Film broken(1, 1);
  broken.restore(16, {std::numeric_limits<double>::infinity(), 0.0, 0.0, 1.0});
  CHECK(broken.per_pixel_relative_error() == std::numeric_limits<double>::infinity());
  broken.restore(16, {std::nan(""), 0.0, 0.0, 1.0});
  CHECK(broken.per_pixel_relative_error() == std::numeric_limits<double>::infinity());
}

TEST_CASE("png: exposure, sRGB curve and clamp", "[image]") {
  CHECK(encode_srgb8(0.0f, 0.0f) == 0);
  CHECK(encode_srgb8(-1.0f, 0.0f) == 0);
  CHECK(encode_srgb8(std::nanf(""), 0.0f) == 0);
  CHECK(encode_srgb8(1.0f, 0.0f) == 255);
  CHECK(encode_srgb8(100.0f, 0.0f) == 255);
  CHECK(encode_srgb8(0.5f, 0.0f) == 188);  // 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354
  CHECK(encode_srgb8(0.25f, 1.0f) == 188);  // one stop up
  CHECK(encode_srgb8(0.002f, 0.0f) == 7);   // linear toe: 12.92 * 0.002 * 255 = 6.6
}

TEST_CASE("options: --sky takes three non-negative numbers", "[options]") {
  CHECK(parse_rgb("1,2.5,0", "--sky") == glm::vec3(1.0f, 2.5f, 0.0f));
  for (const char* bad : {"1,2", "1,2,3,4", "a,b,c", "-1,0,0", "nan,0,0", "1;2;3", ""}) {
    INFO(bad);
    CHECK_THROWS_AS(parse_rgb(bad, "--sky"), Error);
  }
}
