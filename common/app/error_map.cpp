// The per-pixel error map (see error_map.h).
#include "common/app/error_map.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "common/base/error.h"
#include "common/base/srgb.h"

namespace pt {

OutputFile error_map_file(const std::string& path) { return OutputFile(path, "--error-map"); }

namespace {

// Each pixel's variance of its value, spread evenly over the pixels of its 3 x 3 window
// (those inside the image) and gathered back: what each pixel receives is its share of its
// neighbours' variances. A pixel's halves_variance() rests on one degree of freedom, a
// speckle of 0s and spikes; the window gives each about nine, and since every pixel hands
// out exactly what it has, the map's sum of variances, so its RMS, stays the halves' figure.
std::vector<double> spread_over_window(const Film& film) {
  const int w = film.width(), h = film.height();
  auto window = [&](int x, int y) {  // how many pixels the 3 x 3 window around x, y holds
    return (std::min(x + 1, w - 1) - std::max(x - 1, 0) + 1) * (std::min(y + 1, h - 1) - std::max(y - 1, 0) + 1);
  };
  std::vector<double> spread(std::size_t(w) * std::size_t(h), 0.0);
  for (int y = 0; y < h; y++)
    for (int x = 0; x < w; x++) {
      double share = film.halves_variance(x, y) / window(x, y);
      for (int v = std::max(y - 1, 0); v <= std::min(y + 1, h - 1); v++)
        for (int u = std::max(x - 1, 0); u <= std::min(x + 1, w - 1); u++) spread[std::size_t(v) * w + u] += share;
    }
  return spread;
}

}  // namespace

std::vector<float> relative_error_values(const Film& film) {
  std::vector<float> values(std::size_t(film.width()) * std::size_t(film.height()), 0.0f);
  double mean = film.mean_luminance();
  if (film.spp() < 2 || !(mean > 0.0) || !std::isfinite(mean)) return values;
  if (film.per_pixel_error_from_halves()) {
    std::vector<double> variance = spread_over_window(film);
    for (std::size_t i = 0; i < values.size(); i++) values[i] = float(std::sqrt(variance[i]) / mean);
    return values;
  }
  for (int y = 0; y < film.height(); y++)
    for (int x = 0; x < film.width(); x++)
      values[std::size_t(y) * film.width() + x] = float(film.pixel_standard_error(x, y) / mean);
  return values;
}

double error_map_white(const Film& film, double target_error) {
  // White at twice the printed per-pixel error, the RMS of the map's values.
  double e = target_error > 0.0 ? target_error : film.per_pixel_relative_error();
  return e > 0.0 && std::isfinite(e) ? 2.0 * e : 1.0;
}

void write_error_map(const OutputFile& file, const Film& film, double target_error, const ImageMetadata& meta) {
  std::vector<float> values = relative_error_values(film);
  bool png = file.path().size() >= 4 &&
             std::equal(file.path().end() - 4, file.path().end(), ".png",
                        [](char a, char b) { return std::tolower((unsigned char)a) == b; });
  double white = error_map_white(film, target_error);
  std::vector<float> rgb(values.size() * 3);
  for (std::size_t i = 0; i < values.size(); i++) {
    // The linear value that encode_srgb8 turns into the code round(255 g): the map's grey
    // levels are then linear in the error.
    float v = png ? float(srgb_to_linear(std::clamp(double(values[i]) / white, 0.0, 1.0))) : values[i];
    rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = v;
  }
  // The image's description only: the map is a picture, not a part of the render to merge.
  ImageMetadata m;
  m.stage = meta.stage, m.backend = meta.backend, m.scene = meta.scene;
  m.spp = meta.spp, m.seed = meta.seed, m.seconds = meta.seconds;
  file.write(rgb, film.width(), film.height(), m);
}

}  // namespace pt
