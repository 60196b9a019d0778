// Chi-square goodness-of-fit for direction samplers (after Nori's chi2test): samples are
// binned over cos(theta) x phi on the whole sphere, the expected count of each bin is the
// pdf integrated over the bin numerically (8 x 8 Gauss-Legendre points on a grid graded
// towards the pdf's peak and the horizon edge),
// bins expecting fewer than 5 samples are pooled, and the statistic's p-value is compared
// with a Šidák-corrected significance.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include <glm/glm.hpp>

namespace pt::test {

struct Chi2Options {
  int theta_bins = 10;               // bins of cos(theta) over [-1, 1]
  int phi_bins = 20;                 // bins of phi over [0, 2 pi)
  std::uint64_t samples = 1'000'000;
  std::optional<glm::dvec3> peak;    // where the pdf is sharpest (e.g. the mirror direction)
  std::optional<double> z_edge;      // a cos(theta) where the pdf jumps (integrated finely there)
};

struct Chi2Result {
  double statistic = 0.0;
  int dof = 0;
  double p_value = 1.0;
  double integral = 0.0;  // the pdf integrated over the sphere (should be 1)
  std::string table;      // the worst bins, for the failure message
};

// sample: a uniform point of [0,1)^2 to a unit direction; pdf: its solid-angle density.
Chi2Result chi2_test(const std::function<glm::vec3(glm::vec2)>& sample, const std::function<double(glm::dvec3)>& pdf,
                     const Chi2Options& options, std::uint32_t seed);

// P(X >= x) for a chi-square variable with dof degrees of freedom.
double chi2_upper_tail(double x, int dof);

}  // namespace pt::test
