// Built-in scenes: the Cornell box (the default scene of every stage) and, by name, the
// analytic scenes of the tests (analytic_scenes.cpp). Also load_scene(), which picks
// between a built-in scene and a glTF file.
#include <glm/gtc/matrix_transform.hpp>

#include "common/analytic_scenes.h"
#include "common/error.h"
#include "common/scene_loading.h"

namespace pt {

namespace {

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

struct Builtin {
  BuiltinInfo info;
  Scene (*make)();
};

const std::vector<Builtin>& registry() {
  static const std::vector<Builtin> list = {
      {{"cornell", "the Cornell box with its ceiling light (the default scene)"}, cornell},
      {{"furnace", "camera inside a closed box, walls emit 1 with albedo 0.5: Le/(1-albedo) = 2"},
       [] { return analytic::make_furnace({}); }},
      {{"furnace_sphere", "camera inside an emitting sphere (albedo 0.5, Le 1, double-sided): 2"},
       [] { return analytic::make_furnace_sphere({}); }},
      {{"sphere", "a diffuse sphere of radius 1 at distance 4 before a perspective camera"},
       [] { return analytic::make_sphere({}); }},
      {{"quad", "a square turned by 0.5 rad under an orthographic camera"}, [] { return analytic::make_quad({}); }},
      {{"floor_light", "a diffuse floor under a square emitter, seen from below it (Lambert's formula)"},
       [] { return analytic::make_floor_light({}); }},
      {{"mirror", "a mirror reflecting an emitter straight back to the camera: F0 x Le"},
       [] { return analytic::make_mirror({}); }},
      {{"glass_slab", "a glass slab (ior 1.5) before an emitter: Le (1 - R) / (1 + R)"},
       [] { return analytic::make_glass_slab({}); }},
      {{"point_floor", "a diffuse floor under a point light: albedo I cos / (pi d^2) (stage4)"},
       [] { return analytic::make_point_floor({}); }},
      {{"point_in_sphere", "inside a diffuse sphere with a point light of intensity pi at its centre: 1 (stage4)"},
       [] { return analytic::make_point_in_sphere({}); }},
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
      build_light_table(s);
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
  build_light_table(s);
  return s;
}

}  // namespace pt
