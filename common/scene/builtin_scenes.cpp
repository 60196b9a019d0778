// Built-in scenes: the Cornell box (the default scene of every stage) and, by name, the
// analytic scenes of the tests (analytic_scenes.cpp). Also load_scene(), which picks
// between a built-in scene and a glTF file.
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "common/scene/analytic_scenes.h"
#include "common/base/error.h"
#include "common/scene/scene_loading.h"

namespace pt {

namespace {

// The Cornell box's room and light; returns the white material for what goes inside.
uint cornell_room(Scene& s) {
  uint white = s.add_material(make_diffuse({0.73f, 0.73f, 0.73f}));
  uint red = s.add_material(make_diffuse({0.65f, 0.05f, 0.05f}));
  uint green = s.add_material(make_diffuse({0.12f, 0.45f, 0.15f}));
  uint light = s.add_material(make_diffuse({0.78f, 0.78f, 0.78f}, {17.0f, 12.0f, 4.0f}));
  add_room(s, 1.0f, white, white, white, red, green, -1);
  // The ceiling light, a little below the ceiling, facing down.
  float l = 0.25f, y = 0.998f;
  add_quad(s, {-l, y, -l}, {l, y, -l}, {l, y, l}, {-l, y, l}, light);
  CameraDesc cam;
  cam.yfov = 0.6911f;  // 39.6 degrees
  cam.to_world = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 3.9f));
  s.camera = cam;
  return white;
}

// The back wall of cornell_room (its triangles 4 and 5) made textured: a 4 x 4 checkerboard
// of sRGB white and grey repeated twice each way, bilinear, times vertex colours that shade
// its corners pink, green and blue (texture.glsl). With `holes` the wall's alpha is masked
// (alphaMode MASK, cutoff 0.5) and the grey squares (alpha 0.25) are holes in it.
void add_textured_back_wall(Scene& s, bool holes) {
  uint wall = s.add_material(make_diffuse(glm::vec3(0.73f)));
  s.material_textures.assign(s.materials.size(), no_material_textures());
  s.triangle_attributes.assign(s.triangles.size(), no_triangle_attributes());
  const uint white = 0xffffffffu, grey = holes ? 0x40808080u : 0xff808080u;
  s.textures.push_back(Texture{uint(s.texels.size()), 4u, 4u, kWrapRepeat, kWrapRepeat, kFilterLinear, grey, white});
  for (uint y = 0; y < 4; y++) {
    for (uint x = 0; x < 4; x++) s.texels.push_back((x + y) % 2 ? grey : white);
  }
  s.material_textures[wall].base_color = uint(s.textures.size() - 1);
  if (holes) s.material_textures[wall].alpha_cutoff = 0.5f;
  // Corners (-1,-1) (1,-1) (1,1) (-1,1) of the wall, as add_room's quad: triangles 012, 023.
  const glm::vec2 uv[4] = {{0, 2}, {2, 2}, {2, 0}, {0, 0}};
  const glm::vec4 color[4] = {{1.0f, 0.8f, 0.8f, 1.0f}, {0.8f, 1.0f, 0.8f, 1.0f}, {0.8f, 0.8f, 1.0f, 1.0f}, glm::vec4(1.0f)};
  const int corners[2][3] = {{0, 1, 2}, {0, 2, 3}};
  for (int t = 0; t < 2; t++) {
    const int* c = corners[t];
    s.triangles[4 + t].material = wall;
    s.triangle_attributes[4 + t] = TriangleAttributes{uv[c[0]], uv[c[1]], uv[c[2]], glm::vec2(0.0f),
                                                      color[c[0]], color[c[1]], color[c[2]], glm::vec2(0.0f),
                                                      glm::vec2(0.0f)};
  }
  mark_alpha_masked(s);
}

void short_box(Scene& s, uint material) { add_box(s, {0.33f, -0.7f, 0.3f}, {0.3f, 0.3f, 0.3f}, -0.31f, material); }
void tall_box(Scene& s, uint material) { add_box(s, {-0.35f, -0.4f, -0.3f}, {0.3f, 0.6f, 0.3f}, 0.29f, material); }

Scene cornell() {
  Scene s;
  uint white = cornell_room(s);
  short_box(s, white);
  tall_box(s, white);
  return s;
}

// The Cornell box with glossy boxes: a GGX gold-like conductor, roughness 0.3.
Scene cornell_glossy() {
  Scene s;
  cornell_room(s);
  uint gold = s.add_material(make_metal({0.95f, 0.75f, 0.35f}, 0.3f));
  short_box(s, gold);
  tall_box(s, gold);
  return s;
}

// The Cornell box with a glass sphere (ior 1.5) in place of the tall box.
Scene cornell_glass() {
  Scene s;
  uint white = cornell_room(s);
  short_box(s, white);
  s.add_sphere({-0.35f, -0.6f, -0.25f}, 0.4f, s.add_material(make_glass(glm::vec3(1.0f), 1.5f)));
  return s;
}

// Every feature the renderer models in one room (issue "model only what a scene
// requires": the general kernel's own scene): triangles and spheres; diffuse, mirror,
// GGX, glass, rough glass and mixed materials; a textured back wall with vertex colours and holes (an
// alpha mask); emissive triangles, an emissive sphere, a point light and a spot light
// (render it with --sky for the last feature).
Scene every_feature() {
  Scene s;
  cornell_room(s);
  short_box(s, s.add_material(make_metal({0.95f, 0.75f, 0.35f}, 0.3f)));
  tall_box(s, s.add_material(make_gltf_material({0.6f, 0.6f, 0.8f}, 0.5f, 0.2f, 0.0f, 1.5f, {}, false)));
  s.add_sphere({-0.5f, -0.75f, 0.5f}, 0.25f, s.add_material(make_glass(glm::vec3(1.0f), 1.5f)));
  s.add_sphere({0.5f, 0.1f, -0.5f}, 0.2f, s.add_material(make_metal(glm::vec3(0.9f), 0.0f)));
  s.add_sphere({0.0f, 0.6f, 0.3f}, 0.05f, s.add_material(make_diffuse(glm::vec3(0.0f), {20.0f, 20.0f, 30.0f})));
  GltfPbr plastic;  // a glTF file's material: a GGX layer over a base, a quarter metal
  plastic.base = {0.8f, 0.3f, 0.2f}, plastic.metallic = 0.25f, plastic.roughness = 0.4f;
  s.add_sphere({-0.6f, 0.5f, -0.6f}, 0.15f, s.add_material(make_gltf_pbr_material(plastic)));
  // Rough glass (KHR_materials_transmission with roughness 0.3, rough_dielectric.glsl).
  s.add_sphere({0.45f, 0.3f, 0.5f}, 0.15f, s.add_material(make_rough_glass(glm::vec3(0.9f, 1.0f, 0.95f), 1.5f, 0.3f)));
  add_textured_back_wall(s, true);
  // A coarse sphere (20 faces) shaded smooth by its vertex normals (shading_normal.glsl).
  for (const Triangle& t : s.triangles) s.triangle_shading.push_back(flat_shading(t));
  const std::size_t first = s.triangles.size();
  const glm::vec3 center(0.0f, -0.88f, 0.8f);
  add_icosphere(s, center, 0.12f, 1, s.add_material(make_diffuse({0.3f, 0.7f, 0.4f})));
  for (std::size_t i = first; i < s.triangles.size(); i++) {
    Triangle& t = s.triangles[i];
    TriangleShading& sh = s.triangle_shading[i];
    sh.normal0 = glm::normalize(t.p0 - center), sh.normal1 = glm::normalize(t.p1 - center);
    sh.normal2 = glm::normalize(t.p2 - center);
    t.flags |= kTriangleShadingNormals;
  }
  s.point_lights.push_back(make_point_light({0.6f, 0.8f, 0.6f}, {0.3f, 0.3f, 0.2f}));
  s.point_lights.push_back(make_spot_light({-0.6f, 0.9f, -0.6f}, {0.0f, -1.0f, 0.0f}, {0.4f, 0.35f, 0.3f}, 0.3f, 0.5f));
  return s;
}

// Kevin Beason's smallpt (2008), rebuilt from its published numbers: the walls are spheres
// of radius 1e5 (a test of ray/sphere precision in float, intersect.glsl), a mirror and a
// glass ball, and the light a sphere of radius 600 whose cap pokes 0.27 below the ceiling.
// Its camera stands outside the room, behind the black front wall at z = 170, and starts
// its rays 140 units ahead, on a plane inside the room: the camera's clip start.
Scene smallpt() {
  Scene s;
  auto wall = [&](glm::vec3 c, glm::vec3 albedo) { s.add_sphere(c, 1e5f, s.add_material(make_diffuse(albedo))); };
  wall({1e5f + 1.0f, 40.8f, 81.6f}, {0.75f, 0.25f, 0.25f});   // left
  wall({-1e5f + 99.0f, 40.8f, 81.6f}, {0.25f, 0.25f, 0.75f}); // right
  wall({50.0f, 40.8f, 1e5f}, glm::vec3(0.75f));               // back
  wall({50.0f, 1e5f, 81.6f}, glm::vec3(0.75f));               // bottom
  wall({50.0f, -1e5f + 81.6f, 81.6f}, glm::vec3(0.75f));      // top
  wall({50.0f, 40.8f, -1e5f + 170.0f}, glm::vec3(0.0f));      // front, behind the camera's clip start
  s.add_sphere({27.0f, 16.5f, 47.0f}, 16.5f, s.add_material(make_metal(glm::vec3(0.999f), 0.0f)));  // mirror
  s.add_sphere({73.0f, 16.5f, 78.0f}, 16.5f, s.add_material(make_glass(glm::vec3(0.999f), 1.5f)));  // glass
  s.add_sphere({50.0f, 681.6f - 0.27f, 81.6f}, 600.0f, s.add_material(make_diffuse(glm::vec3(0.0f), glm::vec3(12.0f))));
  // The camera at (50, 52, 295.6) looking along (0, -0.042612, -1); smallpt's image plane
  // spans 0.5135 in height at unit distance.
  CameraDesc cam;
  cam.yfov = 2.0f * std::atan(0.5f * 0.5135f);
  cam.to_world = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(50.0f, 52.0f, 295.6f)),
                             -std::atan(0.042612f), glm::vec3(1.0f, 0.0f, 0.0f));
  cam.clip_start = 140.0f;
  s.camera = cam;
  // The room, for the spawn offset's scale: the walls' spheres reach 2e5 away.
  Bounds room;
  room.extend({0.0f, 0.0f, 0.0f});
  room.extend({100.0f, 81.6f, 170.0f});
  s.region = room;
  return s;
}

// The floor under a square light of another size, the same power as builtin:floor_light.
Scene floor_light_sized(float half) {
  analytic::FloorLightScene a;
  a.emission *= (a.light_half * a.light_half) / (half * half);
  a.light_half = half;
  return analytic::make_floor_light(a);
}

struct Builtin {
  BuiltinInfo info;
  Scene (*make)();
};

const std::vector<Builtin>& registry() {
  static const std::vector<Builtin> list = {
      {{"cornell", "the Cornell box with its ceiling light (the default scene)"}, cornell},
      {{"cornell_glossy", "the Cornell box with GGX conductor boxes (roughness 0.3)"}, cornell_glossy},
      {{"cornell_glass", "the Cornell box with a glass sphere (ior 1.5) for the tall box"}, cornell_glass},
      {{"every_feature", "every shape, material and light kind in one room (add --sky for the last)"}, every_feature},
      {{"smallpt", "Beason's smallpt scene: walls as spheres of radius 1e5, a mirror and a glass ball"}, smallpt},
      {{"furnace", "camera inside a closed box, walls emit 1 with albedo 0.5: Le/(1-albedo) = 2"},
       [] { return analytic::make_furnace({}); }},
      {{"furnace_sphere", "camera inside an emitting sphere (albedo 0.5, Le 1, double-sided): 2"},
       [] { return analytic::make_furnace_sphere({}); }},
      {{"furnace_mesh", "camera inside an icosphere of 1.3 M triangles that emit 1 with albedo 0.5: 2"},
       [] { return analytic::make_furnace_mesh({}); }},
      {{"sphere", "a diffuse sphere of radius 1 at distance 4 before a perspective camera"},
       [] { return analytic::make_sphere({}); }},
      {{"quad", "a square turned by 0.5 rad under an orthographic camera"}, [] { return analytic::make_quad({}); }},
      {{"floor_light", "a diffuse floor under a square emitter, seen from below it (Lambert's formula)"},
       [] { return analytic::make_floor_light({}); }},
      {{"floor_small_light", "builtin:floor_light with a light of half-size 0.1 (same power)"},
       [] { return floor_light_sized(analytic::kSmallLightHalf); }},
      {{"floor_large_light", "builtin:floor_light with a light of half-size 2 (same power)"},
       [] { return floor_light_sized(analytic::kLargeLightHalf); }},
      {{"mirror", "a mirror reflecting an emitter straight back to the camera: F0 x Le"},
       [] { return analytic::make_mirror({}); }},
      {{"glass_slab", "a glass slab (ior 1.5) before an emitter: Le (1 - R) / (1 + R)"},
       [] { return analytic::make_glass_slab({}); }},
      {{"point_floor", "a diffuse floor under a point light: albedo I cos / (pi d^2) (stages 4, 5)"},
       [] { return analytic::make_point_floor({}); }},
      {{"spot_floor", "builtin:point_floor with a spot light pointing down (cones 0.4, 1.2 rad): times its falloff"},
       [] {
         analytic::PointFloorScene a;
         a.kind = kPunctualSpot;
         return analytic::make_point_floor(a);
       }},
      {{"sun_floor", "a diffuse floor under a directional light E at cos 0.8 from the vertical: albedo E 0.8 / pi"},
       [] {
         analytic::PointFloorScene a;
         a.kind = kPunctualDirectional;
         return analytic::make_point_floor(a);
       }},
      {{"point_in_sphere", "inside a diffuse sphere with a point light of intensity pi at its centre: 1 (stages 4, 5)"},
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

Scene load_scene(const std::string& spec, const std::string& gltf_scene) {
  const std::string prefix = "builtin:";
  if (spec.rfind(prefix, 0) == 0 && !gltf_scene.empty()) {
    throw Error(kExitBadOption, "--gltf-scene " + gltf_scene + " picks one of a glTF file's scenes; " + spec +
                                    " is built in: leave --gltf-scene out");
  }
  if (spec.rfind(prefix, 0) == 0) return make_builtin_scene(spec.substr(prefix.size()));
  Scene s = load_gltf(spec, gltf_scene);
  s.name = spec;
  build_light_table(s);
  return s;
}

}  // namespace pt
