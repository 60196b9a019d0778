// The film: double-precision accumulation of passes (see film.h).
#include "common/render/film.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace pt {

Film::Film(int width, int height)
    : width_(width), height_(height), sums_(std::size_t(width) * std::size_t(height) * 4, 0.0) {}

void Film::add_pass(std::span<const glm::vec4> pass, std::uint64_t samples) {
  for (std::size_t i = 0; i < pass.size(); i++) {
    for (int c = 0; c < 3; c++) sums_[4 * i + c] += double(pass[i][c]);
    double norm = double(pass[i][3]);  // the root of the pass's sum of squared luminance
    sums_[4 * i + 3] += norm * norm;
  }
  spp_ += samples;
}

void Film::restore(std::uint64_t spp, std::vector<double> sums) {
  if (sums.size() != sums_.size()) throw std::invalid_argument("Film::restore: wrong number of sums");
  sums_ = std::move(sums);
  spp_ = spp;
}

void Film::merge(const Film& other) {
  for (std::size_t i = 0; i < sums_.size(); i++) sums_[i] += other.sums_[i];
  spp_ += other.spp_;
}

glm::dvec3 Film::mean(int x, int y) const {
  if (spp_ == 0) return glm::dvec3(0.0);
  const double* s = &sums_[4 * (std::size_t(y) * width_ + x)];
  return glm::dvec3(s[0], s[1], s[2]) / double(spp_);
}

std::vector<float> Film::mean_rgb() const {
  std::vector<float> rgb(std::size_t(width_) * height_ * 3);
  for (int y = 0; y < height_; y++) {
    for (int x = 0; x < width_; x++) {
      glm::dvec3 m = mean(x, y);
      for (int c = 0; c < 3; c++) rgb[3 * (std::size_t(y) * width_ + x) + c] = float(m[c]);
    }
  }
  return rgb;
}


double Film::sample_variance(int x, int y) const {
  if (spp_ < 2) return 0.0;
  double n = double(spp_);
  const double* s = &sums_[4 * (std::size_t(y) * width_ + x)];
  double sum = luminance(glm::dvec3(s[0], s[1], s[2]));
  return std::max(0.0, (s[3] - sum * sum / n) / (n - 1.0));
}

double Film::mean_luminance() const {
  double sum = 0.0;
  for (int y = 0; y < height_; y++)
    for (int x = 0; x < width_; x++) sum += luminance(mean(x, y));
  return sum / (double(width_) * double(height_));
}

double Film::pixel_standard_error(int x, int y) const {
  return spp_ < 2 ? 0.0 : std::sqrt(sample_variance(x, y) / double(spp_));
}

double Film::per_pixel_relative_error() const {
  if (spp_ < 2) return 0.0;
  double variance_sum = 0.0;  // of the pixels' values: sample variance / spp
  for (int y = 0; y < height_; y++)
    for (int x = 0; x < width_; x++) variance_sum += sample_variance(x, y) / double(spp_);
  double pixels = double(width_) * double(height_);
  double image_mean = mean_luminance();
  if (!std::isfinite(variance_sum) || !std::isfinite(image_mean)) return std::numeric_limits<double>::infinity();
  return image_mean > 0.0 ? std::sqrt(variance_sum / pixels) / image_mean : 0.0;
}

double Film::relative_standard_error() const {
  if (spp_ < 2) return 0.0;
  double variance_sum = 0.0;
  for (int y = 0; y < height_; y++)
    for (int x = 0; x < width_; x++) variance_sum += sample_variance(x, y) / double(spp_);
  double pixels = double(width_) * double(height_);
  double image_mean = mean_luminance();
  return image_mean > 0.0 ? std::sqrt(variance_sum) / pixels / image_mean : 0.0;
}

}  // namespace pt
