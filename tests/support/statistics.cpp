// Statistics for Monte Carlo tests (see statistics.h).
#include "tests/support/statistics.h"

#include <algorithm>
#include <cmath>

namespace pt::test {

double sidak_alpha(double alpha, double n) { return -std::expm1(std::log1p(-alpha) / n); }

namespace {
double log_binomial_pmf(std::uint64_t k, std::uint64_t n, double p) {
  double nk = double(n), kk = double(k);
  double log_choose = std::lgamma(nk + 1.0) - std::lgamma(kk + 1.0) - std::lgamma(nk - kk + 1.0);
  double a = k == 0 ? 0.0 : kk * std::log(p), b = k == n ? 0.0 : (nk - kk) * std::log1p(-p);
  return log_choose + a + b;
}
}  // namespace

double binomial_two_sided_p(std::uint64_t k, std::uint64_t n, double p) {
  if (p <= 0.0) return k == 0 ? 1.0 : 0.0;
  if (p >= 1.0) return k == n ? 1.0 : 0.0;
  double lower = 0.0, upper = 0.0;  // P(X <= k), P(X >= k)
  for (std::uint64_t i = 0; i <= n; i++) {
    double pmf = std::exp(log_binomial_pmf(i, n, p));
    if (i <= k) lower += pmf;
    if (i >= k) upper += pmf;
  }
  return std::min(1.0, 2.0 * std::min(lower, upper));
}

double normal_two_sided_quantile(double alpha) {
  // Solve erfc(z / sqrt 2) = alpha by bisection: slow but exact enough and obvious.
  double lo = 0.0, hi = 40.0;
  for (int i = 0; i < 200; i++) {
    double mid = 0.5 * (lo + hi);
    (std::erfc(mid / std::sqrt(2.0)) > alpha ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double log_slope(const std::vector<double>& n, const std::vector<double>& err) {
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < n.size(); i++) mx += std::log(n[i]) / n.size(), my += std::log(err[i]) / n.size();
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < n.size(); i++) {
    sxy += (std::log(n[i]) - mx) * (std::log(err[i]) - my);
    sxx += (std::log(n[i]) - mx) * (std::log(n[i]) - mx);
  }
  return sxy / sxx;
}

}  // namespace pt::test
