// --error-map's values (common/app/error_map.cpp): each pixel's estimated standard error
// over the image's mean, from the estimate the summary line printed, so that the map's RMS
// is the printed per-pixel error: the sample variance's, or under the default sampler the
// two halves' difference shared over a 3 x 3 window (docs/sampling.md).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "common/app/error_map.h"
#include "common/render/film.h"

using namespace pt;

namespace {

// A film of grey samples value(pixel, k) for k = 0 .. 15, added in the passes the renderer
// runs (1, 1, 2, 4, 8), halves tracked as under the default sampler when `halves`.
Film film_of(int width, int height, bool halves, const std::function<double(int, std::uint64_t)>& value) {
  Film film(width, height);
  if (halves) film.track_halves(0);
  std::uint64_t done = 0;
  for (std::uint64_t n : {1u, 1u, 2u, 4u, 8u}) {
    std::vector<glm::vec4> pass;
    for (int p = 0; p < width * height; p++) {
      double sum = 0.0, squares = 0.0;
      for (std::uint64_t k = done; k < done + n; k++) sum += value(p, k), squares += value(p, k) * value(p, k);
      pass.push_back(glm::vec4(glm::vec3(float(sum)), float(std::sqrt(squares))));
    }
    film.add_pass(pass, n);
    done += n;
  }
  return film;
}

double rms(const std::vector<float>& v) {
  double sum2 = 0.0;
  for (float x : v) sum2 += double(x) * x;
  return std::sqrt(sum2 / double(v.size()));
}

}  // namespace

TEST_CASE("error map: its RMS is the printed per-pixel error, and under the halves each pixel's variance is shared over its 3 x 3 window",
          "[film][cli]") {
  // 8 x 8 pixels, each alternating 0 and 2 (mean 1, sample variance 16/15): their two halves
  // agree. Pixel (5, 2) alternates 0 and 4 in its second half instead: halves' means 1 and 2,
  // so its variance from the halves is ((1 - 2) / 2)^2 = 1/4; the corner (0, 0) likewise.
  const int w = 8, h = 8;
  auto value = [](int p, std::uint64_t k) {
    bool odd = p == 2 * 8 + 5 || p == 0;
    return double(k % 2) * (odd && k >= 8 ? 4.0 : 2.0);
  };
  Film film = film_of(w, h, true, value);
  REQUIRE(film.spp() == 16);
  REQUIRE(film.has_halves());
  // The halves' figure is far below the sample variance's: the summary prints it.
  REQUIRE(film.per_pixel_error_from_halves());
  CHECK(film.per_pixel_relative_error() < 0.4 * film.sample_variance_relative_error());
  std::vector<float> map = relative_error_values(film);
  REQUIRE(map.size() == std::size_t(w * h));
  CHECK(rms(map) == Approx(film.per_pixel_relative_error()).epsilon(1e-6));
  const double mean = film.mean_luminance();
  auto at = [&](int x, int y) { return double(map[std::size_t(y) * w + x]); };
  // Pixel (5, 2) is inside: its 1/4 goes in ninths to the 9 pixels around it.
  for (int y = 1; y <= 3; y++)
    for (int x = 4; x <= 6; x++) CHECK(at(x, y) == Approx(std::sqrt(0.25 / 9.0) / mean).epsilon(1e-5));
  // The corner's window holds 4 pixels: a quarter of its 1/4 to each of them.
  CHECK(at(0, 0) == Approx(std::sqrt(0.25 / 4.0) / mean).epsilon(1e-5));
  CHECK(at(1, 1) == Approx(std::sqrt(0.25 / 4.0) / mean).epsilon(1e-5));
  // Outside both windows: no error (the halves agree there).
  CHECK(at(7, 7) == 0.0f);
  CHECK(at(2, 5) == 0.0f);
  // The PNG's white: twice the printed figure (or the target).
  CHECK(error_map_white(film, 0.0) == Approx(2.0 * film.per_pixel_relative_error()));
  CHECK(error_map_white(film, 0.3) == Approx(0.6));

  // Independent samples (no halves): each pixel's own sample variance, sqrt(s^2 / N) / mean;
  // the RMS is the printed figure again.
  Film plain = film_of(w, h, false, value);
  REQUIRE(!plain.per_pixel_error_from_halves());
  std::vector<float> plain_map = relative_error_values(plain);
  CHECK(rms(plain_map) == Approx(plain.per_pixel_relative_error()).epsilon(1e-6));
  CHECK(plain_map[std::size_t(7 * w + 7)] ==
        Approx(plain.pixel_standard_error(7, 7) / plain.mean_luminance()).epsilon(1e-6));
  CHECK(error_map_white(plain, 0.0) == Approx(2.0 * plain.per_pixel_relative_error()));

  // Halves whose figure is the larger one (they differ by more than the samples spread):
  // the summary and the map take the sample variance's.
  Film apart = film_of(w, h, true, [](int, std::uint64_t k) { return k < 8 ? 1.0 + double(k % 2) * 0.01 : 3.0; });
  REQUIRE(apart.has_halves());
  CHECK(!apart.per_pixel_error_from_halves());
  CHECK(rms(relative_error_values(apart)) == Approx(apart.per_pixel_relative_error()).epsilon(1e-6));
  // Below kMinPixelsForHalves pixels: the sample variance's, halves or not.
  Film small = film_of(4, 4, true, value);
  CHECK(!small.per_pixel_error_from_halves());
  CHECK(rms(relative_error_values(small)) == Approx(small.per_pixel_relative_error()).epsilon(1e-6));
}
