// Closed-form coverage images of builtin:sphere and builtin:quad (see analytic_images.h).
#include "tests/support/analytic_images.h"

#include <cmath>

#include "common/scene/analytic_scenes.h"
#include "tests/support/coverage.h"

namespace pt::test {

namespace {

// The pixel's rectangle in screen coordinates sx, sy in [-1, 1] (sy up, row 0 on top).
Rect pixel_rect(int x, int y, int width, int height) {
  return Rect{2.0 * x / width - 1.0, 1.0 - 2.0 * (y + 1) / height, 2.0 * (x + 1) / width - 1.0,
              1.0 - 2.0 * y / height};
}

}  // namespace

std::vector<double> sphere_coverage(int width, int height) {
  analytic::SphereScene s;
  // A ray at angle theta from the axis meets the sphere iff sin(theta) <= r / d. On the
  // plane at distance 1 that is a disk of radius r / sqrt(d^2 - r^2); the screen maps
  // sx to tan(yfov/2) * aspect * sx and sy to tan(yfov/2) * sy.
  double d = std::abs(double(s.center.z)), r = s.radius;
  double plane_radius = r / std::sqrt(d * d - r * r);
  double ty = std::tan(0.5 * double(s.yfov)), tx = ty * double(width) / double(height);
  std::vector<double> c(std::size_t(width) * height);
  for (int y = 0; y < height; y++) {
    for (int x = 0; x < width; x++) {
      Rect p = pixel_rect(x, y, width, height);
      Rect plane{p.x0 * tx, p.y0 * ty, p.x1 * tx, p.y1 * ty};
      double area = (plane.x1 - plane.x0) * (plane.y1 - plane.y0);
      c[std::size_t(y) * width + x] = disk_rect_area({0.0, 0.0}, plane_radius, plane) / area;
    }
  }
  return c;
}

std::vector<double> quad_coverage(int width, int height) {
  analytic::QuadScene q;
  double h = q.half_size, cs = std::cos(double(q.angle)), sn = std::sin(double(q.angle));
  std::vector<glm::dvec2> square;
  for (glm::dvec2 p : {glm::dvec2(-h, -h), glm::dvec2(h, -h), glm::dvec2(h, h), glm::dvec2(-h, h)}) {
    square.push_back({cs * p.x - sn * p.y, sn * p.x + cs * p.y});
  }
  std::vector<double> c(std::size_t(width) * height);
  for (int y = 0; y < height; y++) {
    for (int x = 0; x < width; x++) {
      Rect p = pixel_rect(x, y, width, height);
      Rect world{p.x0 * q.xmag, p.y0 * q.ymag, p.x1 * q.xmag, p.y1 * q.ymag};
      double area = (world.x1 - world.x0) * (world.y1 - world.y0);
      c[std::size_t(y) * width + x] = polygon_rect_area(square, world) / area;
    }
  }
  return c;
}

}  // namespace pt::test
