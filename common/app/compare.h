// Comparing two renders of one scene within their noise (pt_compare, tools/pt_compare.cpp;
// docs/film.md, "Comparing: pt_compare"). Not in the article: tooling for teachers and for
// regression tests, resting on what makes the article's estimators testable at all: a
// pixel's value is a mean of independent samples, so its noise is estimated from the
// samples themselves (the film's squared-luminance sums, Film::pixel_standard_error).
//
// The statistic, on luminance (the film holds the variance of luminance only):
//   - per pixel i: d_i = L_test(i) - L_ref(i), and each render's estimated variance of one
//     sample, s2_ref(i) and s2_test(i) (Film::sample_variance);
//   - regions (square blocks of `region` pixels, smaller at the right and bottom edges):
//     z = sum d_i / sqrt(V), V = max(sum s2_ref, sum s2_test) x (1/spp_ref + 1/spp_test)
//     + a rounding allowance (kRoundingAllowance times each pixel's larger value, squared,
//     summed): the variance of the summed difference of two independent renders (different
//     seeds) of one image, taking the larger of the two renders' variance estimates. Under
//     the hypothesis that both estimate one image with one estimator either estimate is
//     right; the larger one guards against a render whose few samples never met the rare
//     bright paths that carry part of a pixel's mean (stage2's fireflies): its own
//     variance estimate is then far too small, and with it a Welch-style z (each render's
//     own variance) called a 64-spp stage2 render inconsistent with a 2048-spp one in 1
//     comparison of 3 (docs/film.md);
//   - the image mean: t = sum of the regions' differences / sqrt(sum of their V), or of the
//     halves' bound over the whole image where that is smaller (below);
//   - a pixel's own z (the z-map) is not tested: with few samples its variance estimate is
//     itself noisy and heavy-tailed, while a region's rests on region^2 x spp samples;
//   - every t and z is compared with the normal distribution, two-sided, at the
//     Bonferroni-corrected level alpha / m, m = the number of regions + 1 (the mean): the
//     probability that two unbiased renders are called inconsistent is then at most alpha
//     (up to the normal approximation; docs/film.md gives the false alarms measured).
//   - under randomised QMC (--sampler sobol, the default) a pixel's sample variance over spp
//     overstates the error of its mean, up to hundreds of times on smooth images
//     (docs/sampling.md): the test would be conservative (fewer false alarms, and less
//     power). Where both renders know the halves of their samples (Film::has_halves, kept in
//     the .exr), a region's variance of each render's summed mean is also estimated from
//     them, sum of ((A - B) / 2)^2 over its pixels (an upper bound in expectation under RQMC,
//     with one degree of freedom per pixel), taken as a 99% upper confidence bound (chi-square
//     with Satterthwaite's degrees of freedom estimated cautiously, halves_upper_bound; not
//     where one pixel dominates the region, kHalvesLargestShare) and no smaller than the other
//     render's bound scaled to this one's spp; each render's variance is the smaller of that and
//     its share of the sample variance's figure above. So the halves sharpen the test, and
//     the confidence bound keeps its false alarms at those of the sample variance's figure
//     (measured in docs/film.md). What it cannot see: a bias that keeps luminance (a shift
// of hue), and a bias smaller than the noise of the renders given.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "common/app/film_file.h"
#include "common/render/film.h"

namespace pt {

// Reads a render to compare: an .exr that a stage wrote with --out (film_file.h). Throws
// pt::Error(kExitBadScene), one line naming the file, for a missing or unreadable file and
// for an image without the film's per-pixel variance (a PNG, an HDR, an RGB-only EXR).
FilmPart read_comparable(const std::string& path);

// The relative difference a pixel may have beyond its noise: float rounding, so that two
// noiseless pixels (all samples equal) from two backends still agree.
inline constexpr double kRoundingAllowance = 1e-5;

// The halves' bound: a variance estimated as `sum` of independent one-degree-of-freedom terms
// whose squares sum to sum_of_squares, raised to its upper confidence bound at the normal
// quantile kHalvesBoundZ (2.326: 99%): sum x nu / q, q the chi-square quantile of nu =
// sum^2 / sum_of_squares degrees of freedom by Wilson and Hilferty's approximation; infinity
// where nu is too small for one (about 1.6) and for a sum of 0 (halves that agree exactly in
// every pixel say nothing of the error: the sample variance decides). That nu is Satterthwaite's
// with each term's variance taken from the term itself: about a third of the terms' count
// when they are alike, 1 when one carries the sum, never more than their true degrees of
// freedom in expectation, so the bound is cautious (about 2.4 times the sum for 64 alike
// terms; tests/common/app/test_compare.cpp).
inline constexpr double kHalvesBoundZ = 2.326;
double halves_upper_bound(double sum, double sum_of_squares);
// A region's halves are used only where no pixel holds more than this share of a render's
// summed sample variance there. One pixel whose error is most of the region's has one degree
// of freedom in the halves, and a small draw of it would hide that error (the bound above
// counts it as one term among many); such a pixel (a light's edge, a firefly) shows a large
// sample variance too. What this cannot see: a pixel whose error is most of the region's while
// its sample variance is no larger than its neighbours', i.e. the sampler gains on every
// pixel but that one.
inline constexpr double kHalvesLargestShare = 0.125;

struct CompareSettings {
  double alpha = 0.01;  // the false-alarm rate of the whole comparison (0 < alpha < 1)
  int region = 8;       // the side of a region in pixels (>= 1)
};

// One region's test: pixels x0 ... x1 - 1, y0 ... y1 - 1.
struct RegionTest {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  double ref_mean = 0.0;        // the mean over its pixels of L_ref
  double difference = 0.0;      // the mean over its pixels of L_test - L_ref
  double standard_error = 0.0;  // of that difference
  double z = 0.0;               // difference / standard_error (0 when both are 0)
};

struct Comparison {
  int width = 0, height = 0;
  double ref_mean = 0.0, test_mean = 0.0;  // the images' mean luminance
  double mean_standard_error = 0.0;        // of test_mean - ref_mean
  double mean_t = 0.0;
  int region = 0;                   // the side of a region in pixels
  std::vector<RegionTest> regions;  // row after row of blocks, from the top left
  std::size_t worst = 0;            // the region of the largest |z|
  int tests = 0;                    // regions + 1: the Bonferroni correction's m
  double threshold = 0.0;           // a test fails when |z| > threshold
  bool halves = false;              // both films knew their halves (Film::has_halves)
  int halves_regions = 0;           // regions whose variance took the halves' bound
  bool mean_from_halves = false;    // the mean's variance took the halves' bound over the image
  bool mean_failed = false;
  int failed_regions = 0;
  bool consistent = true;
  // The corrected p-value of the most extreme test: min(1, m x two-sided p). Below alpha
  // exactly when the comparison is not consistent.
  double p_value = 1.0;
  // Per pixel, top row first, for the z-map: d_i / sqrt(max(s2_ref, s2_test) x (1/spp_ref +
  // 1/spp_test) + rounding).
  std::vector<float> pixel_z;
};

// Throws pt::Error(kExitBadScene) naming the file when a film cannot be compared: fewer
// than 2 samples per pixel (no variance), or sums that are not finite numbers; and when the
// two differ in size.
void check_comparable(const Film& ref, const std::string& ref_name, const Film& test, const std::string& test_name);

// The comparison of `test` with `ref` (check_comparable first, with the names "the
// reference" and "the test image"). Throws pt::Error(kExitBadOption) for settings out of range.
Comparison compare_films(const Film& ref, const Film& test, const CompareSettings& settings);

// The z above which a two-sided normal test at level p fails: Phi^-1(1 - p / 2).
double two_sided_threshold(double p);
// The two-sided normal p-value of z: P(|Z| > |z|).
double two_sided_p(double z);

// The z-map picture (--zmap): rgb (width * height * 3, top row first, linear) of the
// comparison. .png: each pixel's z as colour, red where the test is brighter, blue where it
// is darker, black at 0 to full at |z| = 4, with the regions over the threshold outlined
// in yellow; values (.exr): R = the pixel's z, G = its region's z, B = 1 in a failed region.
std::vector<float> zmap_picture(const Comparison& c);
std::vector<float> zmap_values(const Comparison& c);

}  // namespace pt
