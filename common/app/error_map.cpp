// The per-pixel error map (see error_map.h).
#include "common/app/error_map.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "common/base/error.h"
#include "common/base/srgb.h"

namespace pt {

OutputFile error_map_file(const std::string& path) {
  try {
    return OutputFile(path);
  } catch (const Error& e) {  // OutputFile speaks of --out
    std::string message = e.what();
    for (std::size_t at = message.find("--out"); at != std::string::npos; at = message.find("--out", at + 1))
      message.replace(at, 5, "--error-map");
    throw Error(e.code(), message);
  }
}

std::vector<float> relative_error_values(const Film& film) {
  std::vector<float> values(std::size_t(film.width()) * std::size_t(film.height()), 0.0f);
  double mean = film.mean_luminance();
  if (film.spp() < 2 || !(mean > 0.0) || !std::isfinite(mean)) return values;
  for (int y = 0; y < film.height(); y++)
    for (int x = 0; x < film.width(); x++)
      values[std::size_t(y) * film.width() + x] = float(film.pixel_standard_error(x, y) / mean);
  return values;
}

double error_map_white(const Film& film, double target_error) {
  // The map's values are the pixels' sample-variance errors: white at twice their RMS.
  double e = target_error > 0.0 ? target_error : film.sample_variance_relative_error();
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
