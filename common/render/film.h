// The film: per-pixel sums of the samples' radiance, added up pass after pass in double
// precision so that millions of samples stay exact (a float sum stops growing once the
// sum is 2^24 times a sample). Also the sum of squared luminance, for the variance, and for
// randomised QMC the sums at half the samples, for the error of the mean (track_halves).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace pt {

// Rec. 709 luminance of linear RGB, the weights render_pixel.glsl uses for the variance.
inline double luminance(glm::dvec3 c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

// The halves' figure rests on one degree of freedom per pixel: from this many pixels on its
// RMS is known to about 9% (1 / sqrt(2 x 64)), so that --target-error does not stop on a
// lucky draw; a smaller image prints the sample variance's figure (N - 1 per pixel).
constexpr int kMinPixelsForHalves = 64;

class Film {
 public:
  Film(int width, int height);

  // Adds one pass: per pixel (rgb sum, sqrt of the squared-luminance sum) of `samples`
  // samples. The kernels return the root, which a float holds for radiance from 1e-20 to
  // 1e20 (render_pixel.glsl); the film squares it in double (range 1e-308 to 1e308).
  void add_pass(std::span<const glm::vec4> pass, std::uint64_t samples);

  // Adds another film of the same size (independent samples of the same pixels).
  // follows: other's samples are the ones that come right after this film's in the
  // sequence, so that the halves of track_halves() stay known (pt_merge of a render's
  // parts in order); else the film forgets them.
  void merge(const Film& other, bool follows = false);

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
  // each pixel's estimated standard error, divided by the image's mean luminance: when
  // has_halves() and the image has kMinPixelsForHalves pixels or more, the smaller of the
  // halves' figure (track_halves) and sample_variance_relative_error(), two upper bounds
  // under randomised QMC; else the latter, the error of independent samples. 0 if
  // unknown (spp < 2) or for a black image; infinity if the sums are not finite (never
  // trusted to stop a render).
  double per_pixel_relative_error() const;
  // Whether per_pixel_relative_error() took the halves' figure (it then stands for the
  // pixels' halves_variance(), else for their pixel_standard_error()^2): --error-map draws
  // the estimate the summary printed.
  bool per_pixel_error_from_halves() const;
  // The same figure from each pixel's sample variance (pixel_standard_error): the error of
  // independent samples' mean, and an upper bound for randomised QMC (docs/sampling.md).
  double sample_variance_relative_error() const;

  // Randomised QMC (the Owen-scrambled Sobol sampler): a pixel's samples are not
  // independent, and their sample variance over N overstates the error of their mean, the
  // more the better the points cover the domain. From track_halves(first) on, the film keeps
  // each pixel's luminance sum whenever it holds n = 2^k samples that start an aligned block
  // [first, first + 2n) of the sequence; at 2n samples the block's two halves, each a
  // scrambled net, give every pixel an estimate of its error: (mean of one half - mean of the
  // other) / 2, whose square has the expectation Var(mean) - Cov(halves) (Var(mean) exactly
  // for independent samples; above it where the halves' errors cancel, as in a net).
  // first: the sequence index of the film's first sample (--samples FIRST:COUNT).
  void track_halves(std::uint64_t first_sample);
  // Whether the film now holds two such halves (spp a power of two, the block aligned).
  bool has_halves() const { return halves() != nullptr; }
  // The first half (has_halves() only; 0 and empty otherwise): its sample count and each
  // pixel's luminance sum over it, what an .exr keeps of the halves (film_file.h).
  std::uint64_t first_half_spp() const;
  const std::vector<double>& first_half_luminance() const;
  // A film read back from an .exr that kept them: the first half's luminance sums, of
  // half_spp = spp() / 2 samples (else ignored: a film holds halves of its own samples only).
  void restore_halves(std::uint64_t half_spp, std::vector<double> luminance);
  // A pixel's ((mean of one half - mean of the other) / 2)^2: an estimate of the variance of
  // its mean with one degree of freedom (has_halves() only; 0 otherwise). pt_compare sums it
  // over a region (common/app/compare.h).
  double halves_variance(int x, int y) const;
  // Estimated relative standard error of the image's mean luminance (0 if unknown): the
  // per-pixel error over sqrt(pixels) (the pixels' errors are independent), so not the
  // noise a user sees.
  double relative_standard_error() const;

 private:
  int width_, height_;
  std::uint64_t spp_ = 0;
  std::vector<double> sums_;  // per pixel: r, g, b, squared luminance
  // track_halves(): whether it is on, the film's first sample's index, and each pixel's
  // luminance sum at the last two such powers of two (at 2n samples the one at n is the
  // first half, while the one at 2n is kept for 4n).
  struct Snapshot {
    std::uint64_t spp = 0;  // 0: none
    std::vector<double> luminance;
  };
  bool track_halves_ = false;
  std::uint64_t first_sample_ = 0;
  Snapshot snapshots_[2];
  const Snapshot* halves() const;  // the snapshot at spp / 2, if it is kept
  void keep_half();  // keeps the sums if spp_ is such a power of two
  void forget_halves();
  // The sums over pixels of each pixel's estimated variance of its mean: from its sample
  // variance, and from the halves (has_halves() only); relative_rms() turns one into the
  // per-pixel relative error (infinity if it or the image's mean is not finite).
  double sample_variance_sum() const;
  double halves_variance_sum() const;
  // The one of the two that per_pixel_relative_error() takes, and whether it is the halves'.
  struct VarianceSum {
    double sum;
    bool from_halves;
  };
  VarianceSum per_pixel_variance_sum() const;
  double relative_rms(double variance_sum) const;
};

}  // namespace pt
