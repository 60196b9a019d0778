// Exact polygon/disk-rectangle intersection areas (see coverage.h): Sutherland-Hodgman
// clipping with the shoelace formula, and piecewise integration of the circle's chord
// with its antiderivative 0.5 (x s + r^2 asin(x / r)), s = sqrt(r^2 - x^2).
#include "tests/support/coverage.h"

#include <algorithm>
#include <cmath>

namespace pt::test {

namespace {

// Keeps the part of the polygon where dot(p, n) <= d.
std::vector<glm::dvec2> clip(const std::vector<glm::dvec2>& poly, glm::dvec2 n, double d) {
  std::vector<glm::dvec2> out;
  for (std::size_t i = 0; i < poly.size(); i++) {
    glm::dvec2 a = poly[i], b = poly[(i + 1) % poly.size()];
    double da = glm::dot(a, n) - d, db = glm::dot(b, n) - d;
    if (da <= 0.0) out.push_back(a);
    if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) out.push_back(a + (b - a) * (da / (da - db)));
  }
  return out;
}

}  // namespace

double polygon_rect_area(const std::vector<glm::dvec2>& polygon, const Rect& r) {
  std::vector<glm::dvec2> p = polygon;
  p = clip(p, {1, 0}, r.x1);
  p = clip(p, {-1, 0}, -r.x0);
  p = clip(p, {0, 1}, r.y1);
  p = clip(p, {0, -1}, -r.y0);
  double twice = 0.0;
  for (std::size_t i = 0; i < p.size(); i++) {
    glm::dvec2 a = p[i], b = p[(i + 1) % p.size()];
    twice += a.x * b.y - a.y * b.x;
  }
  return std::abs(0.5 * twice);
}

double disk_rect_area(glm::dvec2 c, double radius, const Rect& rect) {
  // Work in the disk's frame.
  Rect r{rect.x0 - c.x, rect.y0 - c.y, rect.x1 - c.x, rect.y1 - c.y};
  double lo = std::max(r.x0, -radius), hi = std::min(r.x1, radius);
  if (lo >= hi) return 0.0;
  auto s = [&](double x) { return std::sqrt(std::max(0.0, radius * radius - x * x)); };
  auto S = [&](double x) {  // antiderivative of s
    double t = std::clamp(x / radius, -1.0, 1.0);
    return 0.5 * (x * s(x) + radius * radius * std::asin(t));
  };
  // Break where the chord's ends cross y0 or y1: there the integrand changes its formula.
  std::vector<double> xs = {lo, hi};
  for (double y : {r.y0, r.y1}) {
    if (std::abs(y) < radius) {
      double x = std::sqrt(radius * radius - y * y);
      for (double b : {-x, x}) {
        if (b > lo && b < hi) xs.push_back(b);
      }
    }
  }
  std::sort(xs.begin(), xs.end());
  double area = 0.0;
  for (std::size_t i = 0; i + 1 < xs.size(); i++) {
    double a = xs[i], b = xs[i + 1], m = 0.5 * (a + b);
    bool top_is_chord = s(m) < r.y1, bottom_is_chord = -s(m) > r.y0;
    double top = top_is_chord ? s(m) : r.y1, bottom = bottom_is_chord ? -s(m) : r.y0;
    if (top <= bottom) continue;
    double integral_top = top_is_chord ? S(b) - S(a) : r.y1 * (b - a);
    double integral_bottom = bottom_is_chord ? -(S(b) - S(a)) : r.y0 * (b - a);
    area += integral_top - integral_bottom;
  }
  return area;
}

}  // namespace pt::test
