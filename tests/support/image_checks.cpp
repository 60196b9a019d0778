// Image checks against closed forms (see image_checks.h).
#include "tests/support/image_checks.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>

#include "cpu/cpu_backend.h"
#include "cpu/wide_bvh.h"
#include "tests/support/statistics.h"
#include "tests/support/test_render.h"

namespace pt::test {

namespace {

// Regularised incomplete beta by continued fraction (Numerical Recipes' betacf idea),
// for the t distribution's tail: P(|T| > t) = I_{dof/(dof+t^2)}(dof/2, 1/2).
double incomplete_beta(double a, double b, double x) {
  if (x <= 0.0) return 0.0;
  if (x >= 1.0) return 1.0;
  double front = std::exp(std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x));
  if (x > (a + 1.0) / (a + b + 2.0)) return 1.0 - incomplete_beta(b, a, 1.0 - x);
  double f = 1.0, c = 1.0, d = 0.0;
  for (int i = 0; i <= 400; i++) {
    int m = i / 2;
    double num;
    if (i == 0) num = 1.0;
    else if (i % 2 == 0) num = (m * (b - m) * x) / ((a + 2.0 * m - 1.0) * (a + 2.0 * m));
    else num = -((a + m) * (a + b + m) * x) / ((a + 2.0 * m) * (a + 2.0 * m + 1.0));
    d = 1.0 + num * d;
    d = std::abs(d) < 1e-300 ? 1e-300 : d;
    d = 1.0 / d;
    c = 1.0 + num / c;
    c = std::abs(c) < 1e-300 ? 1e-300 : c;
    double cd = c * d;
    f *= cd;
    if (std::abs(1.0 - cd) < 1e-15) break;
  }
  return front * (f - 1.0) / a;
}
}  // namespace

double student_two_sided_quantile(double alpha, int dof) {
  double lo = 0.0, hi = 1e6;
  for (int i = 0; i < 200; i++) {
    double t = 0.5 * (lo + hi);
    double tail = incomplete_beta(0.5 * dof, 0.5, dof / (dof + t * t));
    (tail > alpha ? lo : hi) = t;
  }
  return 0.5 * (lo + hi);
}

PixelReport check_pixels(const Film& film, const ExpectedImage& expected, double alpha) {
  const double n = double(film.spp());
  const double pixels = double(film.width()) * film.height();
  const double alpha_pixel = sidak_alpha(alpha, pixels);
  const double z99 = normal_two_sided_quantile(0.01), z_hard = 2.0 * normal_two_sided_quantile(alpha_pixel);
  const double rare = -std::log(alpha_pixel) / n;
  PixelReport report;
  // The allowed count: the smallest k with P(Binomial(pixels, 0.01) > k) < alpha.
  double tail = 1.0;
  for (report.allowed = 0; report.allowed < int(pixels); report.allowed++) {
    tail -= std::exp(std::lgamma(pixels + 1.0) - std::lgamma(report.allowed + 1.0) -
                     std::lgamma(pixels - report.allowed + 1.0) + report.allowed * std::log(0.01) +
                     (pixels - report.allowed) * std::log(0.99));
    if (tail < alpha) break;
  }
  for (int y = 0; y < film.height(); y++) {
    for (int x = 0; x < film.width(); x++) {
      double got = pt::luminance(film.mean(x, y)), want = pt::luminance(expected[std::size_t(y) * film.width() + x]);
      double se = std::sqrt(film.sample_variance(x, y) / n);
      double rounding = 1e-5 * std::abs(want) + 1e-7;
      // A rare outcome (a silhouette pixel's few hits) is seen a handful of times or never:
      // its share of the variance is then mis-estimated. The hard bound allows for an
      // outcome of the size of the pixel with the probability n samples can miss.
      double unseen = se > 0.0 ? 0.0 : rare * (std::abs(got) + std::abs(want));
      double off = std::abs(got - want);
      if (off > z99 * se + unseen + rounding) {
        if (report.outside < 10) UNSCOPED_INFO("pixel " << x << "," << y << ": " << got << ", want " << want << ", standard error " << se);
        report.outside++;
      }
      report.worst = std::max(report.worst, off / (z_hard * se + rare * (std::abs(got) + std::abs(want)) + rounding));
    }
  }
  UNSCOPED_INFO(report.outside << " pixels outside their 99% interval (chance allows " << report.allowed
                                << "), worst pixel at " << report.worst << " of the hard bound");
  return report;
}

double channel_means_ratio(const std::vector<Film>& batches, const ExpectedImage& expected, double alpha,
                           double relative_floor) {
  glm::dvec3 want(0.0);
  for (const glm::dvec3& e : expected) want += e;
  want /= double(expected.size());
  std::vector<glm::dvec3> means;
  for (const Film& f : batches) {
    glm::dvec3 m(0.0);
    for (int y = 0; y < f.height(); y++)
      for (int x = 0; x < f.width(); x++) m += f.mean(x, y);
    means.push_back(m / (double(f.width()) * f.height()));
  }
  const int k = int(means.size());
  const double t_crit = student_two_sided_quantile(sidak_alpha(alpha, 3.0), k - 1);
  double worst = 0.0;
  for (int c = 0; c < 3; c++) {
    double mean = 0.0, var = 0.0;
    for (const glm::dvec3& m : means) mean += m[c] / k;
    for (const glm::dvec3& m : means) var += (m[c] - mean) * (m[c] - mean) / (k - 1);
    double se = std::sqrt(var / k);
    double off = std::max(0.0, std::abs(mean - want[c]) - relative_floor * std::abs(want[c]));
    double ratio = se > 0.0 ? off / se / t_crit : (off <= 1e-6 * std::abs(want[c]) + 1e-9 ? 0.0 : 1e9);
    UNSCOPED_INFO("channel " << c << ": mean " << mean << ", want " << want[c] << ", standard error " << se);
    worst = std::max(worst, ratio);
  }
  return worst;
}

std::vector<Film> render_batches(const StageKernels& kernels, const Scene& scene, RenderSettings settings,
                                 int batches, const Bvh* bvh) {
  std::vector<Film> films;
  std::unique_ptr<Backend> backend = make_backend(backend_under_test, kernels);
  RenderHooks hooks;  // one BVH for all the batches, as a stage's render_frame() builds one
  hooks.bvh = bvh;
  std::optional<Bvh> built;
  if (!bvh && settings.accel == kAccelBvh && !scene.triangles.empty()) hooks.bvh = &built.emplace(build_bvh(scene.triangles));
  // The CPU's 8-wide form of that tree, collapsed once too (each set_scene would collapse
  // it again: 0.15 s a render on the 1.3-million-triangle furnace, issue #51).
  std::optional<WideBvh> wide;
  if (backend_under_test != "gpu" && hooks.bvh && !hooks.bvh->nodes.empty()) {
    give_cpu_wide_bvh(*backend, hooks.bvh, &wide.emplace(build_wide_bvh(*hooks.bvh, scene.triangles)));
  }
  for (int i = 0; i < batches; i++, settings.seed++) films.push_back(render(*backend, scene, settings, hooks).film);
  return films;
}

ExpectedImage expected_image(int width, int height,
                             const std::function<glm::dvec3(double, double, double, double)>& pixel) {
  ExpectedImage image(std::size_t(width) * height);
  for (int y = 0; y < height; y++) {
    for (int x = 0; x < width; x++) {
      image[std::size_t(y) * width + x] = pixel(2.0 * x / width - 1.0, 1.0 - 2.0 * (y + 1) / height,
                                                2.0 * (x + 1) / width - 1.0, 1.0 - 2.0 * y / height);
    }
  }
  return image;
}

ExpectedImage expected_image_by_direction(const Scene& scene, int width, int height,
                                          const std::function<glm::dvec3(glm::dvec3)>& value) {
  const double node[3] = {0.5 - 0.5 * std::sqrt(0.6), 0.5, 0.5 + 0.5 * std::sqrt(0.6)};
  const double weight[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};
  Camera cam = make_camera(scene, float(width) / float(height));
  return expected_image(width, height, [&](double x0, double y0, double x1, double y1) {
    glm::dvec3 sum(0.0);
    for (int i = 0; i < 12; i++) {
      for (int j = 0; j < 12; j++) {
        double sx = x0 + (x1 - x0) * (i / 3 + node[i % 3]) / 4.0, sy = y0 + (y1 - y0) * (j / 3 + node[j % 3]) / 4.0;
        glm::dvec3 dir = glm::normalize(glm::dvec3(cam.forward) + sx * double(cam.extent_x) * glm::dvec3(cam.right) +
                                        sy * double(cam.extent_y) * glm::dvec3(cam.up));
        sum += value(dir) * (weight[i % 3] * weight[j % 3] / 16.0);
      }
    }
    return sum;
  });
}

std::uint32_t ulps(float a, float b) {
  std::int32_t ia, ib;
  std::memcpy(&ia, &a, sizeof a);
  std::memcpy(&ib, &b, sizeof b);
  return ia > ib ? std::uint32_t(ia - ib) : std::uint32_t(ib - ia);
}

std::uint32_t max_ulps(const std::vector<float>& a, const std::vector<float>& b) {
  std::uint32_t worst = 0;
  for (std::size_t i = 0; i < a.size(); i++) {
    std::uint32_t d = ulps(a[i], b[i]);
    if (d != 0) UNSCOPED_INFO("value " << i << ": " << a[i] << " vs " << b[i] << ", " << d << " ulps");
    worst = std::max(worst, d);
  }
  return worst;
}

double agreeing_fraction(const Film& a, const Film& b, double relative) {
  int agree = 0;
  for (int y = 0; y < a.height(); y++) {
    for (int x = 0; x < a.width(); x++) {
      glm::dvec3 u = a.mean(x, y), v = b.mean(x, y);
      bool same = true;
      for (int c = 0; c < 3; c++) same = same && std::abs(u[c] - v[c]) <= 1e-6 + relative * std::abs(u[c]);
      agree += same;
    }
  }
  return double(agree) / (double(a.width()) * a.height());
}

double agreeing_squares_fraction(const Film& a, const Film& b, double relative) {
  const std::vector<double>&u = a.sums(), &v = b.sums();
  std::size_t agree = 0, pixels = u.size() / 4;
  for (std::size_t i = 0; i < pixels && u.size() == v.size(); i++) {
    agree += std::abs(u[4 * i + 3] - v[4 * i + 3]) <= 1e-6 + relative * std::abs(u[4 * i + 3]);
  }
  return double(agree) / double(std::max<std::size_t>(pixels, 1));
}

}  // namespace pt::test
