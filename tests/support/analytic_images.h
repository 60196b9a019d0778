// The closed-form images of the built-in analytic scenes (common/scene/analytic_scenes.h): for
// each pixel the fraction of its area the shape covers, as the camera sees it.
#pragma once

#include <vector>

namespace pt::test {

// builtin:sphere seen by its perspective camera at width x height (square pixels).
std::vector<double> sphere_coverage(int width, int height);

// builtin:quad seen by its orthographic camera at width x height.
std::vector<double> quad_coverage(int width, int height);

}  // namespace pt::test
