// Shape builders of the built-in scenes (scene.h): quads, boxes, rooms and icospheres as
// the scene's triangles. Not part of the article: the scenes the stages render
// (builtin_scenes.cpp, the contract (README.md) "Built-in scenes").
#include "common/scene/scene.h"

#include <algorithm>

#include <glm/gtc/matrix_transform.hpp>

namespace pt {

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

// An icosphere of 20 n^2 triangles (scene.h), watertight.
void add_icosphere(Scene& s, glm::vec3 center, float radius, int n, uint material, bool inward) {
  const float g = 1.6180340f;  // the golden ratio: the icosahedron's corners (0, +-1, +-g) cycled
  const glm::vec3 v[12] = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                           {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  const int faces[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                            {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                            {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  s.triangles.reserve(s.triangles.size() + 20 * std::size_t(n) * std::size_t(n));
  for (const auto& f : faces) {
    glm::vec3 a = v[f[0]], b = v[f[1]], c = v[f[2]];
    if ((glm::dot(glm::cross(b - a, c - a), a + b + c) < 0.0f) != inward) std::swap(b, c);
    // The grid point (i, j) of the face, i + j <= n. On an edge one weight is 0, and adding
    // 0 is exact, so the two faces of the edge compute its points to the same floats.
    auto point = [&](int i, int j) {
      glm::vec3 p = a * (float(n - i - j) / float(n)) + b * (float(i) / float(n)) + c * (float(j) / float(n));
      return center + radius * glm::normalize(p);
    };
    for (int j = 0; j < n; j++) {
      for (int i = 0; i + j < n; i++) {
        s.add_triangle(point(i, j), point(i + 1, j), point(i, j + 1), material);
        if (i + j + 1 < n) s.add_triangle(point(i + 1, j), point(i + 1, j + 1), point(i, j + 1), material);
      }
    }
  }
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

}  // namespace pt
