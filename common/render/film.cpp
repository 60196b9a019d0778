// The film: double-precision accumulation of passes (see film.h).
#include "common/render/film.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "common/kernel/scene_types.h"

namespace pt {

Film::Film(int width, int height)
    : width_(width), height_(height), sums_(std::size_t(width) * std::size_t(height) * 4, 0.0) {}

void Film::add_pass(std::span<const glm::vec4> pass, std::uint64_t samples) {
  for (std::size_t i = 0; i < pass.size(); i++) {
    for (int c = 0; c < 3; c++) sums_[4 * i + c] += double(pass[i][c]);
    double norm = double(pass[i][kPassRootSumSquares]);  // the root of the pass's sum of squared luminance
    sums_[4 * i + 3] += norm * norm;
  }
  spp_ += samples;
  keep_half();
}

void Film::keep_half() {
  // A power of two n whose block [first, first + 2n) is aligned: keep the sums, for the
  // halves at 2n. (The pass schedule ends a pass at every power of two: render.h.)
  if (track_halves_ && spp_ > 0 && (spp_ & (spp_ - 1)) == 0 && first_sample_ % (2 * spp_) == 0) {
    // Over the older of the two: the newer one may be this count's first half.
    Snapshot& s = snapshots_[0].spp < snapshots_[1].spp ? snapshots_[0] : snapshots_[1];
    s.luminance.resize(std::size_t(width_) * std::size_t(height_));
    for (std::size_t i = 0; i < s.luminance.size(); i++)
      s.luminance[i] = luminance(glm::dvec3(sums_[4 * i], sums_[4 * i + 1], sums_[4 * i + 2]));
    s.spp = spp_;
  }
}

const Film::Snapshot* Film::halves() const {
  for (const Snapshot& s : snapshots_)
    if (s.spp > 0 && 2 * s.spp == spp_) return &s;
  return nullptr;
}

void Film::track_halves(std::uint64_t first_sample) {
  track_halves_ = true;
  first_sample_ = first_sample;
  forget_halves();
  keep_half();  // the samples it already holds (a resumed render, a merge's first part)
}

std::uint64_t Film::first_half_spp() const {
  const Snapshot* half = halves();
  return half ? half->spp : 0;
}

const std::vector<double>& Film::first_half_luminance() const {
  static const std::vector<double> none;
  const Snapshot* half = halves();
  return half ? half->luminance : none;
}

void Film::restore_halves(std::uint64_t half_spp, std::vector<double> luminance) {
  if (half_spp == 0 || 2 * half_spp != spp_ || luminance.size() != std::size_t(width_) * std::size_t(height_)) return;
  forget_halves();
  snapshots_[0] = Snapshot{half_spp, std::move(luminance)};
}

void Film::forget_halves() {
  for (Snapshot& s : snapshots_) s = Snapshot{};
}

void Film::restore(std::uint64_t spp, std::vector<double> sums) {
  if (sums.size() != sums_.size()) throw std::invalid_argument("Film::restore: wrong number of sums");
  sums_ = std::move(sums);
  spp_ = spp;
  forget_halves();
}

void Film::merge(const Film& other, bool follows) {
  for (std::size_t i = 0; i < sums_.size(); i++) sums_[i] += other.sums_[i];
  spp_ += other.spp_;
  if (follows) {
    keep_half();  // as if other's samples were one more pass
  } else {
    track_halves_ = false;  // the halves of which samples: not known
    forget_halves();
  }
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
  return spp_ < 2 ? 0.0 : relative_rms(per_pixel_variance_sum().sum);
}

bool Film::per_pixel_error_from_halves() const {
  return spp_ >= 2 && per_pixel_variance_sum().from_halves;
}

Film::VarianceSum Film::per_pixel_variance_sum() const {
  // Both are upper bounds of the error under randomised QMC (film.h): the smaller one, the
  // halves' only where enough pixels average its one degree of freedom per pixel.
  const double samples = sample_variance_sum();
  const bool enough = double(width_) * double(height_) >= double(kMinPixelsForHalves);
  if (!has_halves() || !enough) return {samples, false};
  const double halves = halves_variance_sum();
  return halves < samples ? VarianceSum{halves, true} : VarianceSum{samples, false};
}

double Film::sample_variance_relative_error() const {
  return spp_ < 2 ? 0.0 : relative_rms(sample_variance_sum());
}

double Film::sample_variance_sum() const {
  double variance_sum = 0.0;  // of the pixels' values: sample variance / spp
  for (int y = 0; y < height_; y++)
    for (int x = 0; x < width_; x++) variance_sum += sample_variance(x, y) / double(spp_);
  return variance_sum;
}

double Film::halves_variance(int x, int y) const {
  const Snapshot* half = halves();
  if (half == nullptr) return 0.0;
  const std::size_t i = std::size_t(y) * std::size_t(width_) + std::size_t(x);
  const double h = double(half->spp);
  const double all = luminance(glm::dvec3(sums_[4 * i], sums_[4 * i + 1], sums_[4 * i + 2]));
  const double d = 0.5 * (half->luminance[i] / h - (all - half->luminance[i]) / h);  // (A - B) / 2
  return d * d;
}

double Film::halves_variance_sum() const {
  double variance_sum = 0.0;  // of the pixels' values
  for (int y = 0; y < height_; y++)
    for (int x = 0; x < width_; x++) variance_sum += halves_variance(x, y);
  return variance_sum;
}

double Film::relative_rms(double variance_sum) const {
  double pixels = double(width_) * double(height_);
  double image_mean = mean_luminance();
  if (!std::isfinite(variance_sum) || !std::isfinite(image_mean)) return std::numeric_limits<double>::infinity();
  return image_mean > 0.0 ? std::sqrt(variance_sum / pixels) / image_mean : 0.0;
}

double Film::relative_standard_error() const {
  // The pixels' errors are independent (each pixel has its own sequence), so the image
  // mean's variance is the sum of theirs over pixels^2: the per-pixel figure's variances,
  // whichever estimate that figure took (film.h), over sqrt(pixels).
  return per_pixel_relative_error() / std::sqrt(double(width_) * double(height_));
}

}  // namespace pt
