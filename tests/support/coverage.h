// Closed-form pixel coverage: the exact area of a convex polygon or a disk inside an
// axis-aligned rectangle. The analytic images of stage1 are coverage times colour.
#pragma once

#include <vector>

#include <glm/glm.hpp>

namespace pt::test {

struct Rect {
  double x0, y0, x1, y1;  // x0 < x1, y0 < y1
};

// Area of (convex polygon, vertices in order) intersected with the rectangle.
double polygon_rect_area(const std::vector<glm::dvec2>& polygon, const Rect& r);

// Area of (disk of the given centre and radius) intersected with the rectangle.
double disk_rect_area(glm::dvec2 center, double radius, const Rect& r);

}  // namespace pt::test
