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
#include <vector>

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
  std::uint64_t not_unit = 0;    // samples whose length is not 1 (to 1e-4): not directions at all
  std::uint64_t non_finite = 0;  // samples with a NaN or infinite component (binned nowhere)
  std::string table;      // the worst bins, for the failure message
  // The histogram against the pdf, bin by bin (row: cos theta from -1 up, column: phi), for
  // the picture a student looks at (histogram_picture.h).
  int theta_bins = 0, phi_bins = 0;
  std::vector<double> observed, expected;
};

// sample: a uniform point of [0,1)^2 to a unit direction; pdf: its solid-angle density.
// The bins see only a sample's direction (cos theta, phi), so a sampler that returns vectors
// of another length is counted apart (not_unit): it must be 0 for a fit.
Chi2Result chi2_test(const std::function<glm::vec3(glm::vec2)>& sample, const std::function<double(glm::dvec3)>& pdf,
                     const Chi2Options& options, std::uint32_t seed);

// The density in solid angle that a mapping from the unit square to directions gives at u:
// 1 / |dw/du1 x dw/du2|, the area a small square of u covers on the sphere (central
// differences). It holds whatever the mapping's convention (which number sets theta, u or
// 1 - u), so comparing it with the sampler's own pdf tests the pair without a fixed inverse.
double mapping_density(const std::function<glm::vec3(glm::vec2)>& sample, glm::vec2 u);

// How many points of a 10 x 10 grid of u (0.05, 0.15, ..., 0.95) have a mapping density
// that differs from pdf(sample(u)) by more than 1%. 0 for a sampler that matches its pdf.
int mapping_density_mismatches(const std::function<glm::vec3(glm::vec2)>& sample,
                               const std::function<double(glm::dvec3)>& pdf, std::string* first = nullptr);

// P(X >= x) for a chi-square variable with dof degrees of freedom.
double chi2_upper_tail(double x, int dof);

}  // namespace pt::test
