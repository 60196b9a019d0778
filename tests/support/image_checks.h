// Checks of a rendered image against the image known in closed form, with tolerances
// derived from the variance the film estimated (never tuned to a seed): every pixel by a
// z-test of its luminance, Šidák-corrected over the image; the image mean per channel by
// a t-test over independent batches.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "common/render/backend.h"
#include "common/render/film.h"
#include "common/render/render.h"
#include "common/scene/scene.h"

namespace pt::test {

using ExpectedImage = std::vector<glm::dvec3>;  // width * height, row 0 on top

// Per pixel, the luminance of the mean against the expected one, in units of the pixel's
// estimated standard error. Path-tracing estimates are skewed (rare bright paths), so the
// normal distribution is trusted only at moderate z: the image passes when
//  - no more pixels lie outside their 99% interval than Binomial(pixels, 0.01) allows at
//    level alpha (a bias shows up as many such pixels), and
//  - no pixel lies beyond 2 x the Šidák-corrected z (a single broken pixel shows up).
// A rare outcome is seen a handful of times or never, and its share of the variance is
// then mis-estimated: both bounds allow, where every sample was the same, and the hard
// bound always, for an outcome as large as the pixel with probability -ln(alpha_pixel)/n
// (what n samples miss with probability alpha_pixel).
struct PixelReport {
  int outside = 0;       // pixels outside their 99% interval
  int allowed = 0;       // how many of those chance explains at level alpha
  double worst = 0.0;    // largest |error| / (hard bound); <= 1 passes
  bool passed() const { return outside <= allowed && worst <= 1.0; }
};
PixelReport check_pixels(const Film& film, const ExpectedImage& expected, double alpha = 1e-3);

// The image mean of each channel, over batches rendered with independent seeds, against
// the expected image's mean: a two-sided t-test at level alpha (Šidák over 3 channels).
// Returns the largest |t| divided by its critical value (<= 1 passes).
// relative_floor: a difference up to this fraction of the expected mean is not counted (a
// known precision limit of the renderer or of the closed form, stated where it is used).
double channel_means_ratio(const std::vector<Film>& batches, const ExpectedImage& expected, double alpha = 1e-3,
                           double relative_floor = 0.0);

// Renders `batches` films of settings.spp each with seeds seed, seed + 1, ..., on the
// backend under test; `bvh`: the scene's BVH built already (else built once here).
std::vector<Film> render_batches(const StageKernels& kernels, const Scene& scene, RenderSettings settings,
                                 int batches, const Bvh* bvh = nullptr);

// Expected image from a function of the pixel's screen rectangle [x0,x1] x [y0,y1] in
// [-1, 1] screen coordinates (y up): the function averages over the rectangle itself.
ExpectedImage expected_image(int width, int height,
                             const std::function<glm::dvec3(double x0, double y0, double x1, double y1)>& pixel);

// Expected image of `scene` through its camera when the radiance seen along each direction
// is `value(direction)`: each pixel the mean of it over the pixel, by 3-point Gauss-Legendre
// on 4 x 4 cells (the Fresnel term changes by a third across a pixel near the horizon: a
// midpoint rule of 8 x 8 points is off by 1e-4 of it, above the float rounding that
// stage5's exact samples show).
ExpectedImage expected_image_by_direction(const Scene& scene, int width, int height,
                                          const std::function<glm::dvec3(glm::dvec3 direction)>& value);

// Student's t quantile: P(|T| > t) = alpha for dof degrees of freedom.
double student_two_sided_quantile(double alpha, int dof);

// Distance in units in the last place between two finite floats of the same sign, and the
// largest such distance between two images' values (each value that differs is reported).
std::uint32_t ulps(float a, float b);
std::uint32_t max_ulps(const std::vector<float>& a, const std::vector<float>& b);

// Two renders that should agree to rounding (CPU and GPU, BVH and none): the fraction of
// pixels whose every channel agrees within `relative` (1e-5 unless said) or 1e-6 absolute.
double agreeing_fraction(const Film& a, const Film& b, double relative = 1e-5);
// The same for each pixel's sum of squared sample luminances (Film::sums()'s fourth value),
// from which the per-pixel error the summary prints is estimated: the kernels' own
// kPassRootSumSquares, which the tests of that estimate's honesty run on the CPU only.
double agreeing_squares_fraction(const Film& a, const Film& b, double relative = 1e-5);

}  // namespace pt::test
