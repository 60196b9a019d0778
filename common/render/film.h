// The film: per-pixel sums of the samples' radiance, added up pass after pass in double
// precision so that millions of samples stay exact (a float sum stops growing once the
// sum is 2^24 times a sample). Also the sum of squared luminance, for the variance.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace pt {

// Rec. 709 luminance of linear RGB, the weights render_pixel.glsl uses for the variance.
inline double luminance(glm::dvec3 c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

class Film {
 public:
  Film(int width, int height);

  // Adds one pass: per pixel (rgb sum, sqrt of the squared-luminance sum) of `samples`
  // samples. The kernels return the root, which a float holds for radiance from 1e-20 to
  // 1e20 (render_pixel.glsl); the film squares it in double (range 1e-308 to 1e308).
  void add_pass(std::span<const glm::vec4> pass, std::uint64_t samples);

  // Adds another film of the same size (independent samples of the same pixels).
  void merge(const Film& other);

  int width() const { return width_; }
  int height() const { return height_; }
  std::uint64_t spp() const { return spp_; }

  // The raw sums (per pixel r, g, b, squared luminance), for checkpoints; restore() puts
  // saved ones back (sums.size() must be width * height * 4).
  const std::vector<double>& sums() const { return sums_; }
  void restore(std::uint64_t spp, std::vector<double> sums);

  // The pixel's value: the mean radiance of its samples (box filter).
  glm::dvec3 mean(int x, int y) const;
  // The image as float RGB, row after row from the top (what image_output writes).
  std::vector<float> mean_rgb() const;
  // Estimated variance of one sample's luminance at a pixel (unbiased, needs spp >= 2).
  double sample_variance(int x, int y) const;
  // The image's mean luminance: the mean over pixels of luminance(mean(x, y)).
  double mean_luminance() const;
  // Estimated standard error of the pixel's value (its luminance): sqrt(sample variance /
  // spp), the noise a user sees in that pixel (0 below 2 spp).
  double pixel_standard_error(int x, int y) const;
  // The per-pixel relative error (the summary line, --target-error): the RMS over pixels of
  // pixel_standard_error, divided by the image's mean luminance. 0 if unknown (spp < 2) or
  // for a black image; infinity if the sums are not finite (never trusted to stop a render).
  double per_pixel_relative_error() const;
  // Estimated relative standard error of the image's mean luminance (0 if unknown): about
  // sqrt(pixels) times smaller than the per-pixel error, so not the noise a user sees.
  double relative_standard_error() const;

 private:
  int width_, height_;
  std::uint64_t spp_ = 0;
  std::vector<double> sums_;  // per pixel: r, g, b, squared luminance
};

}  // namespace pt
