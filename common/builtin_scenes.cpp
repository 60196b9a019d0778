// Built-in scenes: the Cornell box (the default scene of every stage) and the analytic
// scenes of the tests (analytic_scenes.h). Also load_scene(), which picks between a
// built-in scene and a glTF file.
#include <cmath>
#include <functional>

#include <glm/gtc/matrix_transform.hpp>

#include "common/analytic_scenes.h"
#include "common/error.h"
#include "common/scene_loading.h"

namespace pt {

namespace {

// A quad p0 p1 p2 p3 (counter-clockwise seen from its front) as two triangles.
void add_quad(Scene& s, glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, glm::vec3 p3, uint material) {
  s.add_triangle(p0, p1, p2, material);
  s.add_triangle(p0, p2, p3, material);
}

// An axis-aligned box of half-size `half` turned by `angle` about +Y, faces outwards.
void add_box(Scene& s, glm::vec3 center, glm::vec3 half, float angle, uint material) {
  glm::mat4 m = glm::translate(glm::mat4(1.0f), center) * glm::rotate(glm::mat4(1.0f), angle, glm::vec3(0, 1, 0));
  auto p = [&](float x, float y, float z) { return glm::vec3(m * glm::vec4(x * half.x, y * half.y, z * half.z, 1.0f)); };
  add_quad(s, p(-1, -1, 1), p(1, -1, 1), p(1, 1, 1), p(-1, 1, 1), material);      // +z
  add_quad(s, p(1, -1, -1), p(-1, -1, -1), p(-1, 1, -1), p(1, 1, -1), material);  // -z
  add_quad(s, p(1, -1, 1), p(1, -1, -1), p(1, 1, -1), p(1, 1, 1), material);      // +x
  add_quad(s, p(-1, -1, -1), p(-1, -1, 1), p(-1, 1, 1), p(-1, 1, -1), material);  // -x
  add_quad(s, p(-1, 1, 1), p(1, 1, 1), p(1, 1, -1), p(-1, 1, -1), material);      // +y
  add_quad(s, p(-1, -1, -1), p(1, -1, -1), p(1, -1, 1), p(-1, -1, 1), material);  // -y
}

// The inside of the cube [-h, h]^3, every face turned inwards.
void add_room(Scene& s, float h, uint floor, uint ceiling, uint back, uint left, uint right, int front) {
  add_quad(s, {-h, -h, h}, {h, -h, h}, {h, -h, -h}, {-h, -h, -h}, floor);   // y = -h, facing +y
  add_quad(s, {-h, h, -h}, {h, h, -h}, {h, h, h}, {-h, h, h}, ceiling);     // y = +h, facing -y
  add_quad(s, {-h, -h, -h}, {h, -h, -h}, {h, h, -h}, {-h, h, -h}, back);    // z = -h, facing +z
  add_quad(s, {-h, -h, h}, {-h, -h, -h}, {-h, h, -h}, {-h, h, h}, left);    // x = -h, facing +x
  add_quad(s, {h, -h, -h}, {h, -h, h}, {h, h, h}, {h, h, -h}, right);       // x = +h, facing -x
  if (front >= 0) add_quad(s, {h, -h, h}, {-h, -h, h}, {-h, h, h}, {h, h, h}, uint(front));  // facing -z
}

Scene cornell() {
  Scene s;
  uint white = s.add_material(make_diffuse({0.73f, 0.73f, 0.73f}));
  uint red = s.add_material(make_diffuse({0.65f, 0.05f, 0.05f}));
  uint green = s.add_material(make_diffuse({0.12f, 0.45f, 0.15f}));
  uint light = s.add_material(make_diffuse({0.78f, 0.78f, 0.78f}, {17.0f, 12.0f, 4.0f}));
  add_room(s, 1.0f, white, white, white, red, green, -1);
  // The ceiling light, a little below the ceiling, facing down.
  float l = 0.25f, y = 0.998f;
  add_quad(s, {-l, y, -l}, {l, y, -l}, {l, y, l}, {-l, y, l}, light);
  add_box(s, {0.33f, -0.7f, 0.3f}, {0.3f, 0.3f, 0.3f}, -0.31f, white);   // short box
  add_box(s, {-0.35f, -0.4f, -0.3f}, {0.3f, 0.6f, 0.3f}, 0.29f, white);  // tall box
  CameraDesc cam;
  cam.yfov = 0.6911f;  // 39.6 degrees
  cam.to_world = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 3.9f));
  s.camera = cam;
  return s;
}

Scene furnace() {
  analytic::FurnaceScene f;
  Scene s;
  uint wall = s.add_material(make_diffuse(glm::vec3(f.albedo), glm::vec3(f.emission)));
  add_room(s, f.half_size, wall, wall, wall, wall, wall, int(wall));
  CameraDesc cam;
  cam.yfov = 1.2f;
  s.camera = cam;  // at the centre, looking down -Z
  return s;
}

Scene sphere() {
  analytic::SphereScene a;
  Scene s;
  s.add_sphere(a.center, a.radius, s.add_material(make_diffuse(a.color)));
  CameraDesc cam;
  cam.yfov = a.yfov;
  s.camera = cam;
  return s;
}

Scene quad() {
  analytic::QuadScene a;
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
  return s;
}

struct Builtin {
  BuiltinInfo info;
  Scene (*make)();
};

const std::vector<Builtin>& registry() {
  static const std::vector<Builtin> list = {
      {{"cornell", "the Cornell box with its ceiling light (the default scene)"}, cornell},
      {{"furnace", "camera inside a closed box, walls emit 1 with albedo 0.5: Le/(1-albedo) = 2"}, furnace},
      {{"sphere", "a diffuse sphere of radius 1 at distance 4 before a perspective camera"}, sphere},
      {{"quad", "a square turned by 0.5 rad under an orthographic camera"}, quad},
  };
  return list;
}

}  // namespace

const std::vector<BuiltinInfo>& builtin_scenes() {
  static const std::vector<BuiltinInfo> infos = [] {
    std::vector<BuiltinInfo> v;
    for (const Builtin& b : registry()) v.push_back(b.info);
    return v;
  }();
  return infos;
}

Scene make_builtin_scene(const std::string& name) {
  for (const Builtin& b : registry()) {
    if (b.info.name == name) {
      Scene s = b.make();
      s.name = "builtin:" + name;
      return s;
    }
  }
  std::string names;
  for (const Builtin& b : registry()) names += (names.empty() ? "" : ", ") + b.info.name;
  throw Error(kExitBadScene, "unknown built-in scene 'builtin:" + name + "'; the built-in scenes are " + names);
}

Scene load_scene(const std::string& spec) {
  const std::string prefix = "builtin:";
  if (spec.rfind(prefix, 0) == 0) return make_builtin_scene(spec.substr(prefix.size()));
  Scene s = load_gltf(spec);
  s.name = spec;
  return s;
}

}  // namespace pt
