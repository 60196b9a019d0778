// The film, the pass schedule, PNG encoding and option parsing: the machinery around the
// integrators (common/render/film.h, render.h, image_output.h, options.h).
#include <catch2/catch.hpp>

#include <cmath>
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

TEST_CASE("render: passes double up to the cap, independent of timing", "[film]") {
  CHECK(pass_samples(0) == 1);
  CHECK(pass_samples(1) == 2);
  CHECK(pass_samples(3) == 8);
  CHECK(pass_samples(4) == kMaxPassSamples);
  CHECK(pass_samples(1000) == kMaxPassSamples);
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
