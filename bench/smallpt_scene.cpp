// The scene of pt_smallpt_reference (bench/smallpt_reference.cpp, issue #18's yardstick):
// smallpt's spheres with builtin:smallpt's numbers (common/scene/builtin_scenes.cpp), its
// optional black front wall, and the camera's image plane.
#include "bench/smallpt_scene.h"

namespace pt::bench::smallpt {

Scene smallpt_scene(int width, int height, bool front_wall) {
  Scene s;
  auto wall = [&](V3 c, V3 a) { s.spheres.push_back({c, 1e5, a, {}, Kind::Diffuse}); };
  wall({1e5 + 1, 40.8, 81.6}, {0.75, 0.25, 0.25});   // left
  wall({-1e5 + 99, 40.8, 81.6}, {0.25, 0.25, 0.75});  // right
  wall({50, 40.8, 1e5}, {0.75, 0.75, 0.75});          // back
  if (front_wall) wall({50, 40.8, -1e5 + 170}, {0, 0, 0});
  wall({50, 1e5, 81.6}, {0.75, 0.75, 0.75});          // bottom
  wall({50, -1e5 + 81.6, 81.6}, {0.75, 0.75, 0.75});  // top
  s.spheres.push_back({{27, 16.5, 47}, 16.5, {0.999, 0.999, 0.999}, {}, Kind::Mirror});
  s.spheres.push_back({{73, 16.5, 78}, 16.5, {0.999, 0.999, 0.999}, {}, Kind::Glass});
  s.spheres.push_back({{50, 681.6 - 0.27, 81.6}, 600, {}, {12, 12, 12}, Kind::Diffuse});
  s.eye = {50, 52, 295.6};
  s.forward = unit({0, -0.042612, -1});
  // The image plane at unit distance: 0.5135 high, width / height times that wide; cy is
  // "up" (perpendicular to the horizontal cx and to the view direction).
  const double plane_h = 0.5135;
  s.cx = {plane_h * width / height, 0, 0};
  s.cy = unit(cross(s.cx, s.forward)) * plane_h;
  return s;
}

}  // namespace pt::bench::smallpt
