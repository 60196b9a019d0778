// Lambert's formula for the irradiance a uniformly emitting polygon gives a point
// (Lambert 1760; Arvo 1995): E = (Le / 2) sum_k Theta_k (Gamma_k . n), Theta_k the angle
// the k-th edge subtends at the point and Gamma_k the unit normal of the plane through the
// point and that edge. The closed form behind the "floor under a square light" images.
#pragma once

#include <vector>

#include <glm/glm.hpp>

namespace pt::test {

// The polygon (convex, wholly above the point's tangent plane) of radiance Le.
double polygon_irradiance(const std::vector<glm::dvec3>& polygon, glm::dvec3 point, glm::dvec3 normal, double Le);

// The mean of f over [x0,x1] x [y0,y1] by 6 x 6 Gauss-Legendre points (smooth f), in each of
// cells x cells equal parts of the rectangle (for an f with a kink inside).
double rect_average(double x0, double y0, double x1, double y1, double (*f)(double, double, const void*),
                    const void* data, int cells = 1);

}  // namespace pt::test
