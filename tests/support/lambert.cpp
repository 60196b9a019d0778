// Lambert's polygon formula and a Gauss-Legendre pixel average (see lambert.h).
#include "tests/support/lambert.h"

#include <algorithm>
#include <cmath>

namespace pt::test {

double polygon_irradiance(const std::vector<glm::dvec3>& polygon, glm::dvec3 point, glm::dvec3 normal, double Le) {
  double sum = 0.0;
  for (std::size_t k = 0; k < polygon.size(); k++) {
    glm::dvec3 a = glm::normalize(polygon[k] - point);
    glm::dvec3 b = glm::normalize(polygon[(k + 1) % polygon.size()] - point);
    double theta = std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0));
    sum += theta * glm::dot(glm::normalize(glm::cross(a, b)), normal);
  }
  return 0.5 * Le * std::abs(sum);
}

double rect_average(double x0, double y0, double x1, double y1, double (*f)(double, double, const void*),
                    const void* data, int cells) {
  if (cells > 1) {
    double sum = 0.0, dx = (x1 - x0) / cells, dy = (y1 - y0) / cells;
    for (int i = 0; i < cells; i++) {
      for (int j = 0; j < cells; j++) {
        sum += rect_average(x0 + i * dx, y0 + j * dy, x0 + (i + 1) * dx, y0 + (j + 1) * dy, f, data, 1);
      }
    }
    return sum / (double(cells) * cells);
  }
  static const double nodes[6] = {-0.9324695142031521, -0.6612093864662645, -0.2386191860831969,
                                  0.2386191860831969,  0.6612093864662645,  0.9324695142031521};
  static const double weights[6] = {0.1713244923791704, 0.3607615730481386, 0.4679139345726910,
                                    0.4679139345726910, 0.3607615730481386, 0.1713244923791704};
  double sum = 0.0;
  for (int i = 0; i < 6; i++) {
    for (int j = 0; j < 6; j++) {
      double x = 0.5 * (x0 + x1) + 0.5 * (x1 - x0) * nodes[i];
      double y = 0.5 * (y0 + y1) + 0.5 * (y1 - y0) * nodes[j];
      sum += weights[i] * weights[j] * f(x, y, data);
    }
  }
  return sum / 4.0;
}

}  // namespace pt::test
