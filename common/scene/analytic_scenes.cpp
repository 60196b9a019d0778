// The built-in analytic scenes (analytic_scenes.h): scenes whose every pixel is known in
// closed form, which the tests of every stage render (docs/testing.md).
#include "common/scene/analytic_scenes.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace pt::analytic {

Scene make_furnace(const FurnaceScene& f) {
  Scene s;
  uint wall = s.add_material(make_diffuse(glm::vec3(f.albedo), glm::vec3(f.emission)));
  add_room(s, f.half_size, wall, wall, wall, wall, wall, int(wall));
  CameraDesc cam;
  cam.yfov = 1.2f;
  s.camera = cam;  // at the centre, looking down -Z
  build_light_table(s);
  return s;
}

Scene make_furnace_sphere(const FurnaceSphereScene& f) {
  Scene s;
  s.add_sphere(glm::vec3(0.0f), f.radius,
               s.add_material(make_diffuse(glm::vec3(f.albedo), glm::vec3(f.emission), true)));
  CameraDesc cam;
  cam.yfov = 1.2f;
  s.camera = cam;  // at the centre, looking down -Z
  build_light_table(s);
  return s;
}

Scene make_furnace_mesh(const FurnaceMeshScene& f) {
  Scene s;
  uint wall = s.add_material(make_diffuse(glm::vec3(f.albedo), glm::vec3(f.emission), true));
  add_icosphere(s, glm::vec3(0.0f), f.radius, f.n, wall, true);
  CameraDesc cam;
  cam.yfov = 1.2f;
  s.camera = cam;  // at the centre, looking down -Z
  build_light_table(s);
  return s;
}

Scene make_floor_light(const FloorLightScene& a) {
  Scene s;
  uint floor = s.add_material(make_diffuse(glm::vec3(a.albedo)));
  uint light = s.add_material(make_diffuse(glm::vec3(0.0f), a.emission));
  float h = a.floor_half, l = a.light_half, y = a.light_height;
  add_quad(s, {-h, 0, h}, {h, 0, h}, {h, 0, -h}, {-h, 0, -h}, floor);   // facing +y
  if (a.triangle && a.turned_away) {
    s.add_triangle({-l, y, -l}, {l, y, l}, {l, y, -l}, light);  // facing +y
  } else if (a.triangle) {
    s.add_triangle({-l, y, -l}, {l, y, -l}, {l, y, l}, light);  // facing -y
  } else if (a.turned_away) {
    add_quad(s, {-l, y, -l}, {-l, y, l}, {l, y, l}, {l, y, -l}, light);  // facing +y
  } else {
    add_quad(s, {-l, y, -l}, {l, y, -l}, {l, y, l}, {-l, y, l}, light);  // facing -y
  }
  s.camera = orthographic_down({0.0f, a.camera_height, 0.0f}, a.view_half);
  build_light_table(s);
  return s;
}

Scene make_mirror(const MirrorScene& a) {
  Scene s;
  uint mirror = s.add_material(make_metal(a.f0, 0.0f));
  uint light = s.add_material(make_diffuse(glm::vec3(0.0f), a.emission));
  float m = 3.0f, e = 4.0f, z = a.emitter_z;
  add_quad(s, {-m, -m, 0}, {m, -m, 0}, {m, m, 0}, {-m, m, 0}, mirror);  // facing +z
  add_quad(s, {e, -e, z}, {-e, -e, z}, {-e, e, z}, {e, e, z}, light);    // facing -z
  s.camera = orthographic_front(a.camera_z, 1.0f);
  build_light_table(s);
  return s;
}

Scene make_glass_slab(const GlassSlabScene& a) {
  Scene s;
  uint glass = s.add_material(make_glass(glm::vec3(1.0f), a.ior));
  uint light = s.add_material(make_diffuse(glm::vec3(0.0f), glm::vec3(a.emission)));
  add_box(s, glm::vec3(0.0f), {3.0f, 3.0f, a.half_thickness}, 0.0f, glass);
  float e = 6.0f;
  add_quad(s, {-e, -e, -3}, {e, -e, -3}, {e, e, -3}, {-e, e, -3}, light);  // facing +z
  s.camera = orthographic_front(a.camera_z, 1.0f);
  build_light_table(s);
  return s;
}

Scene make_sphere(const SphereScene& a) {
  Scene s;
  s.add_sphere(a.center, a.radius, s.add_material(make_diffuse(a.color)));
  CameraDesc cam;
  cam.yfov = a.yfov;
  s.camera = cam;
  build_light_table(s);
  return s;
}

Scene make_quad(const QuadScene& a) {
  Scene s;
  uint m = s.add_material(make_diffuse(a.color));
  float c = std::cos(a.angle), n = std::sin(a.angle), h = a.half_size;
  auto p = [&](float x, float y) { return glm::vec3(c * x - n * y, n * x + c * y, 0.0f); };
  add_quad(s, p(-h, -h), p(h, -h), p(h, h), p(-h, h), m);
  CameraDesc cam;
  cam.kind = kCameraOrthographic;
  cam.xmag = a.xmag, cam.ymag = a.ymag;
  cam.to_world = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 5.0f));
  s.camera = cam;
  build_light_table(s);
  return s;
}

double spot_falloff(double inner, double outer, double theta) {
  double t = std::clamp((std::cos(theta) - std::cos(outer)) / std::max(1e-3, std::cos(inner) - std::cos(outer)), 0.0, 1.0);
  return t * t;
}

Scene make_point_floor(const PointFloorScene& a) {
  Scene s;
  uint floor = s.add_material(make_diffuse(glm::vec3(a.floor.albedo)));
  float h = a.floor.floor_half;
  add_quad(s, {-h, 0, h}, {h, 0, h}, {h, 0, -h}, {-h, 0, -h}, floor);
  const glm::vec3 position(0.0f, a.floor.light_height, 0.0f), down(0.0f, -1.0f, 0.0f);
  if (a.kind == kPunctualPoint) s.point_lights.push_back(make_point_light(position, a.intensity));
  if (a.kind == kPunctualSpot) s.point_lights.push_back(make_spot_light(position, down, a.intensity, a.inner, a.outer));
  if (a.kind == kPunctualDirectional) {
    glm::vec3 along(std::sin(a.sun_angle), -std::cos(a.sun_angle), 0.0f);
    s.point_lights.push_back(make_directional_light(along, a.intensity));
  }
  s.camera = orthographic_down({0.0f, a.floor.camera_height, 0.0f}, a.floor.view_half);
  build_light_table(s);
  return s;
}

Scene make_point_in_sphere(const PointInSphereScene& a) {
  Scene s;
  s.add_sphere(glm::vec3(0.0f), a.radius, s.add_material(make_diffuse(glm::vec3(a.albedo))));
  s.point_lights.push_back(make_point_light(glm::vec3(0.0f), glm::vec3(a.intensity)));
  CameraDesc cam;
  cam.yfov = 1.2f;
  s.camera = cam;  // at the centre, looking down -Z
  build_light_table(s);
  return s;
}

}  // namespace pt::analytic
