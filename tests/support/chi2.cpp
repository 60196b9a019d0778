// Chi-square goodness-of-fit for direction samplers (see chi2.h).
#include "tests/support/chi2.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <utility>
#include <vector>

namespace pt::test {

namespace {

// Breakpoints of [a, b] graded geometrically towards `toward` (halving down to 1e-12), so
// that a peak of any width there is resolved; `graded` false: twelve equal pieces (the
// pdf may jump where the half vector meets the horizon).
std::vector<double> breaks(double a, double b, double toward, bool graded) {
  std::vector<double> x = {a, b};
  if (!graded) {
    for (int i = 1; i < 12; i++) x.push_back(a + (b - a) * i / 12.0);
  } else {
    double p = std::clamp(toward, a, b);
    x.push_back(p);
    for (double d = 0.5 * (b - a); d > 1e-12; d *= 0.5) {
      if (p - d > a) x.push_back(p - d);
      if (p + d < b) x.push_back(p + d);
    }
  }
  std::sort(x.begin(), x.end());
  x.erase(std::unique(x.begin(), x.end()), x.end());
  return x;
}

// The integral of the pdf over z in [z0, z1], phi in [p0, p1] (solid angle dz dphi): 8 x 8
// Gauss-Legendre points on each cell of a grid graded towards the peak when it is near.
double bin_integral(const std::function<double(glm::dvec3)>& pdf, double z0, double z1, double p0, double p1,
                    bool near_peak, double peak_z, double peak_phi, bool peak_at_pole, std::optional<double> z_edge) {
  static const double nodes[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                                  -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                                  0.7966664774136267,  0.9602898564975363};
  static const double weights[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                                    0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                                    0.2223810344533745, 0.1012285362903763};
  bool edge_here = z_edge && *z_edge > z0 && *z_edge < z1;
  std::vector<double> zs = breaks(z0, z1, edge_here ? *z_edge : peak_z, near_peak || edge_here);
  std::vector<double> ps = breaks(p0, p1, peak_phi, near_peak && !peak_at_pole);
  double total = 0.0;
  for (std::size_t i = 0; i + 1 < zs.size(); i++) {
    double zc = 0.5 * (zs[i] + zs[i + 1]), zh = 0.5 * (zs[i + 1] - zs[i]);
    for (std::size_t j = 0; j + 1 < ps.size(); j++) {
      double pc = 0.5 * (ps[j] + ps[j + 1]), ph = 0.5 * (ps[j + 1] - ps[j]);
      double cell = 0.0;
      for (int a = 0; a < 8; a++) {
        double z = zc + zh * nodes[a], r = std::sqrt(std::max(0.0, 1.0 - z * z));
        for (int b = 0; b < 8; b++) {
          double phi = pc + ph * nodes[b];
          cell += weights[a] * weights[b] * pdf(glm::dvec3(r * std::cos(phi), r * std::sin(phi), z));
        }
      }
      total += cell * zh * ph;
    }
  }
  return total;
}

// Regularised upper incomplete gamma Q(a, x) (series below a + 1, continued fraction above).
double gamma_q(double a, double x) {
  if (x <= 0.0) return 1.0;
  double log_front = a * std::log(x) - x - std::lgamma(a);
  if (x < a + 1.0) {
    double term = 1.0 / a, sum = term;
    for (int n = 1; n < 1000; n++) {
      term *= x / (a + n);
      sum += term;
      if (term < sum * 1e-16) break;
    }
    return 1.0 - std::exp(log_front) * sum;
  }
  double b = x + 1.0 - a, c = 1e300, d = 1.0 / b, h = d;
  for (int i = 1; i < 1000; i++) {
    double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    d = std::abs(d) < 1e-300 ? 1e-300 : d;
    c = b + an / c;
    c = std::abs(c) < 1e-300 ? 1e-300 : c;
    d = 1.0 / d;
    double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < 1e-16) break;
  }
  return std::exp(log_front) * h;
}

}  // namespace

double mapping_density(const std::function<glm::vec3(glm::vec2)>& sample, glm::vec2 u) {
  const float h = 1e-3f;
  glm::dvec3 d1 = (glm::dvec3(sample(u + glm::vec2(h, 0.0f))) - glm::dvec3(sample(u - glm::vec2(h, 0.0f)))) / (2.0 * h);
  glm::dvec3 d2 = (glm::dvec3(sample(u + glm::vec2(0.0f, h))) - glm::dvec3(sample(u - glm::vec2(0.0f, h)))) / (2.0 * h);
  return 1.0 / glm::length(glm::cross(d1, d2));
}

int mapping_density_mismatches(const std::function<glm::vec3(glm::vec2)>& sample,
                               const std::function<double(glm::dvec3)>& pdf, std::string* first) {
  int mismatches = 0;
  for (int i = 0; i < 10; i++) {
    for (int j = 0; j < 10; j++) {
      const glm::vec2 u(0.05f + 0.1f * float(i), 0.05f + 0.1f * float(j));
      const double mapped = mapping_density(sample, u), declared = pdf(glm::dvec3(sample(u)));
      if (std::abs(mapped - declared) <= 1e-2 * std::abs(declared)) continue;
      if (mismatches++ == 0 && first) {
        std::ostringstream t;
        t << "at u = (" << u.x << ", " << u.y << ") the mapping's density is " << mapped << " and the pdf says "
          << declared;
        *first = t.str();
      }
    }
  }
  return mismatches;
}

double chi2_upper_tail(double x, int dof) { return gamma_q(0.5 * dof, 0.5 * x); }

Chi2Result chi2_test(const std::function<glm::vec3(glm::vec2)>& sample, const std::function<double(glm::dvec3)>& pdf,
                     const Chi2Options& o, std::uint32_t seed) {
  const int bins = o.theta_bins * o.phi_bins;
  std::vector<double> observed(bins, 0.0), expected(bins, 0.0);
  Chi2Result r;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (std::uint64_t i = 0; i < o.samples; i++) {
    glm::vec3 w = sample(glm::vec2(u(rng), u(rng)));
    if (!std::isfinite(w.x) || !std::isfinite(w.y) || !std::isfinite(w.z)) {
      r.non_finite++;  // and missing from the bins
      continue;
    }
    if (std::abs(glm::length(glm::dvec3(w)) - 1.0) > 1e-4) r.not_unit++;
    double z = std::clamp(double(w.z), -1.0, 1.0), phi = std::atan2(double(w.y), double(w.x));
    if (phi < 0.0) phi += 2.0 * M_PI;
    int ti = std::min(o.theta_bins - 1, int((z + 1.0) * 0.5 * o.theta_bins));
    int pi = std::min(o.phi_bins - 1, int(phi / (2.0 * M_PI) * o.phi_bins));
    observed[ti * o.phi_bins + pi] += 1.0;
  }
  // Where the pdf peaks: its bin and the bins around it get a graded grid.
  double peak_z = 2.0, peak_phi = 0.0;
  int peak_ti = -10, peak_pi = -10;
  bool pole = false;
  if (o.peak) {
    peak_z = std::clamp(o.peak->z, -1.0, 1.0);
    peak_phi = std::atan2(o.peak->y, o.peak->x);
    if (peak_phi < 0.0) peak_phi += 2.0 * M_PI;
    pole = std::abs(peak_z) > 1.0 - 1e-6;
    peak_ti = std::min(o.theta_bins - 1, int((peak_z + 1.0) * 0.5 * o.theta_bins));
    peak_pi = std::min(o.phi_bins - 1, int(peak_phi / (2.0 * M_PI) * o.phi_bins));
  }
  for (int ti = 0; ti < o.theta_bins; ti++) {
    for (int pi = 0; pi < o.phi_bins; pi++) {
      double z0 = -1.0 + 2.0 * ti / o.theta_bins, z1 = -1.0 + 2.0 * (ti + 1) / o.theta_bins;
      double p0 = 2.0 * M_PI * pi / o.phi_bins, p1 = 2.0 * M_PI * (pi + 1) / o.phi_bins;
      int dphi = std::abs(pi - peak_pi);
      dphi = std::min(dphi, o.phi_bins - dphi);
      bool near = std::abs(ti - peak_ti) <= 1 && (pole || dphi <= 1);
      double p = bin_integral(pdf, z0, z1, p0, p1, near, peak_z, peak_phi, pole, o.z_edge);
      r.integral += p;
      expected[ti * o.phi_bins + pi] = p * double(o.samples);
    }
  }
  // Pool the bins that expect fewer than 5 samples into one.
  std::vector<int> order(bins);
  for (int i = 0; i < bins; i++) order[i] = i;
  double pooled_obs = 0.0, pooled_exp = 0.0;
  std::vector<std::pair<double, int>> contributions;
  int cells = 0;
  for (int i = 0; i < bins; i++) {
    if (expected[i] < 5.0) {
      pooled_obs += observed[i], pooled_exp += expected[i];
      continue;
    }
    double d = observed[i] - expected[i];
    r.statistic += d * d / expected[i];
    contributions.push_back({d * d / expected[i], i});
    cells++;
  }
  if (pooled_exp >= 5.0 || (pooled_obs > 0.0 && pooled_exp > 0.0)) {
    double d = pooled_obs - pooled_exp;
    r.statistic += d * d / std::max(pooled_exp, 1e-300);
    cells++;
  } else if (pooled_obs > 0.0) {
    r.statistic = 1e300;  // samples where the pdf says none can be
  }
  r.dof = std::max(1, cells - 1);
  r.p_value = chi2_upper_tail(r.statistic, r.dof);
  std::sort(contributions.rbegin(), contributions.rend());
  std::ostringstream t;
  t << r.not_unit << " samples not of unit length, " << r.non_finite << " not finite; chi2 " << r.statistic << " dof " << r.dof << " p " << r.p_value << " pdf integral " << r.integral
    << "; pooled observed " << pooled_obs << " expected " << pooled_exp << "; worst bins:";
  for (std::size_t k = 0; k < std::min<std::size_t>(4, contributions.size()); k++) {
    int i = contributions[k].second;
    t << " [cos " << i / o.phi_bins << ", phi " << i % o.phi_bins << "] observed " << observed[i] << " expected "
      << expected[i] << ";";
  }
  r.table = t.str();
  r.theta_bins = o.theta_bins, r.phi_bins = o.phi_bins;
  r.observed = std::move(observed), r.expected = std::move(expected);
  return r;
}

}  // namespace pt::test
