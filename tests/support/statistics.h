// Statistics for Monte Carlo tests: exact binomial tests, Šidák-corrected significance,
// normal quantiles, Student t-tests. Tolerances come from these, never from a lucky seed.
#pragma once

#include <cstdint>
#include <vector>

namespace pt::test {

// Per-test significance so that n independent tests together reject with probability alpha.
double sidak_alpha(double alpha, double n);

// Two-sided p-value of observing k successes in n Bernoulli(p) trials (exact).
double binomial_two_sided_p(std::uint64_t k, std::uint64_t n, double p);

// z with P(|Z| > z) = alpha for a standard normal Z.
double normal_two_sided_quantile(double alpha);

// Least-squares slope of log(err) against log(n): a convergence rate (-1/2 for independent
// samples).
double log_slope(const std::vector<double>& n, const std::vector<double>& err);

}  // namespace pt::test
