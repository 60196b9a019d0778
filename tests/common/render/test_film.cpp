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

// Randomised QMC (the default sampler): a pixel's samples are not independent, so the
// error comes from the means of the two halves of its samples, each an aligned block of
// the sequence (Film::track_halves, docs/sampling.md).
TEST_CASE("film: under track_halves the per-pixel error comes from the two halves' means at powers of two",
          "[film]") {
  // Even pixels: sample k of the first 16 alternates 0 and 2 in the first half (mean 1) and
  // 0 and 3 in the second (mean 1.5); odd pixels are a constant 2 (white). Passes as the
  // schedule runs them: 1, 1, 2, 4, 8, 16, 16 samples. 64 pixels (kMinPixelsForHalves).
  auto sample = [](std::uint64_t k, std::uint64_t count) {
    return double(k % 2) * (k < count / 2 ? 2.0 : 3.0);
  };
  auto run = [&](Film& film, std::uint64_t last) {
    std::uint64_t done = 0;
    for (std::uint64_t n : {1u, 1u, 2u, 4u, 8u, 16u, 16u}) {
      if (done + n > last) break;
      double sum = 0.0, squares = 0.0;
      for (std::uint64_t k = done; k < done + n; k++) sum += sample(k, last), squares += sample(k, last) * sample(k, last);
      std::vector<glm::vec4> pass;
      for (int p = 0; p < kMinPixelsForHalves / 2; p++) {
        pass.push_back(glm::vec4(glm::vec3(float(sum)), float(std::sqrt(squares))));
        pass.push_back(glm::vec4(glm::vec3(2.0f * float(n)), 2.0f * std::sqrt(float(n))));
      }
      film.add_pass(pass, n);
      done += n;
    }
  };
  const double image_mean = (1.25 + 2.0) / 2.0;
  // Pixel 0's samples: eight 0, four 2, four 3; sample variance (52 - 16 x 1.25^2) / 15.
  const double sample_variance_error = std::sqrt(0.5 * (27.0 / 15.0) / 16.0) / image_mean;
  Film film(2, 32);
  film.track_halves(0);
  run(film, 16);
  REQUIRE(film.spp() == 16);
  CHECK(film.has_halves());
  // Halves' means 1 and 1.5: the pixel's error (1.5 - 1) / 2; pixel 1's is 0. RMS over the
  // two pixels, over the image mean. Below the sample variance's figure, which stays at
  // hand (error maps).
  CHECK(film.per_pixel_relative_error() == Approx(std::sqrt(0.5 * 0.25 * 0.25) / image_mean));
  CHECK(film.sample_variance_relative_error() == Approx(sample_variance_error));
  // The image mean's error follows the same estimate: over sqrt(pixels).
  CHECK(film.relative_standard_error() == Approx(film.per_pixel_relative_error() / 8.0));
  // Of the two upper bounds, the smaller: halves that differ by more than the samples'
  // spread (here 0 and 2, then 4 and 6) give way to the sample variance's figure.
  Film apart(8, 8);
  apart.track_halves(0);
  for (float v : {0.0f, 2.0f, 4.0f, 6.0f}) apart.add_pass(std::vector<glm::vec4>(64, glm::vec4(v, v, v, v)), 1);
  REQUIRE(apart.has_halves());
  CHECK(apart.per_pixel_relative_error() == Approx(apart.sample_variance_relative_error()));
  // Fewer than kMinPixelsForHalves pixels: the sample variance's figure, halves or not.
  Film small(2, 1);
  small.track_halves(0);
  for (float v : {0.0f, 2.0f, 0.0f, 2.0f}) small.add_pass(std::vector<glm::vec4>(2, glm::vec4(v, v, v, v)), 1);
  REQUIRE(small.has_halves());
  CHECK(small.per_pixel_relative_error() == Approx(small.sample_variance_relative_error()));

  // Without track_halves (independent samples), the sample variance's figure.
  Film plain(2, 32);
  run(plain, 16);
  CHECK(!plain.has_halves());
  CHECK(plain.per_pixel_relative_error() == Approx(plain.sample_variance_relative_error()));
  CHECK(plain.sample_variance_relative_error() == Approx(sample_variance_error));

  // 48 samples (a pass end, not a power of two): no two aligned halves, the sample variance's figure.
  Film past(2, 32);
  past.track_halves(0);
  run(past, 64);
  REQUIRE(past.spp() == 48);
  CHECK(!past.has_halves());
  CHECK(past.per_pixel_relative_error() == Approx(past.sample_variance_relative_error()));

  // Samples 16 .. 31 (--samples 16:16) are an aligned block: halves 16 .. 23 and 24 .. 31.
  Film part(2, 32);
  part.track_halves(16);
  run(part, 16);
  CHECK(part.has_halves());
  CHECK(part.per_pixel_relative_error() == Approx(std::sqrt(0.5 * 0.25 * 0.25) / image_mean));
  // Samples 8 .. 23 are not: its halves would be 8 .. 15 and 16 .. 23, not one net split in two.
  Film shifted(2, 32);
  shifted.track_halves(8);
  run(shifted, 16);
  CHECK(!shifted.has_halves());

  // Merged or restored films do not know their halves.
  Film merged = film;
  merged.merge(plain);
  CHECK(!merged.has_halves());
  Film restored(2, 32);
  restored.track_halves(0);
  restored.restore(film.spp(), film.sums());
  CHECK(!restored.has_halves());
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
