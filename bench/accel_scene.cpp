// pt_bench's acceleration section (accel.h): the scenes whose triangle counts span 36 to
// 1.3 million, made in memory. An icosphere is the icosahedron's 20 triangles, each split
// into 4 by its edges' midpoints pushed out to the sphere, `level` times over: 20 * 4^level
// triangles, of nearly equal size, closed (the midpoint of an edge is computed from the
// same two vertices on both of its triangles, a + b = b + a in float, so the mesh has no
// cracks). It sits in the Cornell room, so that diffuse bounce rays have walls to hit.
#include <cmath>
#include <stdexcept>

#include "bench/accel.h"
#include "bench/bench.h"

namespace pt::bench {

namespace {

// Where the sphere sits in the room (bench/make_sphere_mesh.py's placement).
const glm::vec3 kSphereCenter(0.0f, -0.45f, 0.0f);
const float kSphereRadius = 0.5f;
const float kYfov = 0.6911f;  // the Cornell box camera's field of view

void subdivide(Scene& s, glm::vec3 a, glm::vec3 b, glm::vec3 c, int level, uint material) {
  if (level == 0) {
    s.add_triangle(kSphereCenter + kSphereRadius * a, kSphereCenter + kSphereRadius * b,
                   kSphereCenter + kSphereRadius * c, material);
    return;
  }
  glm::vec3 ab = glm::normalize(a + b), bc = glm::normalize(b + c), ca = glm::normalize(c + a);
  subdivide(s, a, ab, ca, level - 1, material);
  subdivide(s, ab, b, bc, level - 1, material);
  subdivide(s, ca, bc, c, level - 1, material);
  subdivide(s, ab, bc, ca, level - 1, material);
}

void add_icosphere(Scene& s, int level, uint material) {
  const float g = 0.5f * (1.0f + std::sqrt(5.0f));  // the golden ratio
  const glm::vec3 v[12] = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                           {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  const int faces[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                            {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                            {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  s.triangles.reserve(s.triangles.size() + (std::size_t(20) << (2 * level)));
  for (const auto& f : faces) {
    glm::vec3 a = glm::normalize(v[f[0]]), b = glm::normalize(v[f[1]]), c = glm::normalize(v[f[2]]);
    if (glm::dot(glm::cross(b - a, c - a), a + b + c) < 0.0f) std::swap(b, c);  // front faces outward
    subdivide(s, a, b, c, level, material);
  }
}

}  // namespace

Scene accel_scene(int level) {
  Scene s = load_bench_scene("cornell");
  if (level < 0) return s;
  // builtin:cornell is the room (5 walls, the light: 12 triangles) and then the two boxes.
  const std::size_t room = 12;
  if (s.triangles.size() != room + 24) throw std::logic_error("builtin:cornell is no longer room + two boxes");
  s.triangles.resize(room);
  s.name = accel_scene_name(level);
  add_icosphere(s, level, s.triangles[0].material);  // the walls' white
  return s;
}

std::string accel_scene_name(int level) {
  if (level < 0) return "builtin:cornell";
  return "room + icosphere " + std::to_string(level);
}

Camera accel_camera() {
  // On the sphere's axis in front of the room's open side, far enough that the sphere
  // fills 90% of the image's height; the corners see the floor, the walls and the back.
  const float half = 0.5f * kYfov;
  const float distance = kSphereRadius / std::sin(0.9f * half);
  Camera c{};
  c.kind = kCameraPerspective;
  c.origin = kSphereCenter + glm::vec3(0.0f, 0.0f, distance);
  c.forward = glm::vec3(0.0f, 0.0f, -1.0f);
  c.right = glm::vec3(1.0f, 0.0f, 0.0f);
  c.up = glm::vec3(0.0f, 1.0f, 0.0f);
  c.extent_x = c.extent_y = std::tan(half);
  return c;
}

}  // namespace pt::bench
