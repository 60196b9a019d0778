// Random triangle scenes for the BVH tests (see random_scenes.h).
#include "tests/support/random_scenes.h"

#include <cmath>

namespace pt::test {

float add_random_triangles(Scene& s, std::mt19937& rng, int index, int count) {
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::uniform_int_distribution<int> exponent(-6, 6);
  uint m = s.add_material(make_diffuse(glm::vec3(0.5f)));
  const float scale = std::pow(10.0f, float(exponent(rng)));  // 1e-6 ... 1e6
  const glm::vec3 offset = scale * float(index % 3) * 50.0f * glm::vec3(unit(rng), unit(rng), unit(rng));
  auto point = [&] { return offset + scale * glm::vec3(unit(rng), unit(rng), unit(rng)); };
  for (int i = 0; i < count; i++) {
    glm::vec3 a = point(), b = 0.2f * (point() - a) + a, c = 0.2f * (point() - a) + a;
    if (i % 7 == 3) c = a + 1e-4f * (b - a);  // a sliver
    if (i % 9 == 4) c = b;                     // zero area
    if (i % 13 == 9) {                         // a copy: equal distances
      const Triangle& earlier = s.triangles[std::size_t(i) / 3];
      a = earlier.p0, b = earlier.p1, c = earlier.p2;
    }
    if (i % 11 == 5 && i > 0) a = s.triangles.back().p1, b = s.triangles.back().p0;  // a shared edge
    s.add_triangle(a, b, c, m);
  }
  return scale;
}

void add_copied_grid(Scene& s, int n) {
  uint m = s.add_material(make_diffuse(glm::vec3(0.5f)));
  for (int copy = 0; copy < 3; copy++) {
    for (int x = 0; x < n; x++) {
      for (int y = 0; y < n; y++) {
        add_quad(s, {float(x), float(y), 5}, {float(x + 1), float(y), 5}, {float(x + 1), float(y + 1), 5},
                 {float(x), float(y + 1), 5}, m);
      }
    }
  }
}

void add_spread_triangles(Scene& s, std::mt19937& rng, int count) {
  uint m = s.add_material(make_diffuse(glm::vec3(0.5f)));
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  for (int i = 0; i < count; i++) {
    float size = std::pow(10.0f, -6.0f + 12.0f * float(i) / float(count));
    glm::vec3 c = size * glm::vec3(unit(rng), unit(rng), unit(rng));
    s.add_triangle(c, c + size * glm::vec3(unit(rng), unit(rng), 0.1f), c + size * glm::vec3(0.1f, unit(rng), unit(rng)), m);
  }
}

void random_test_ray(const Scene& s, std::mt19937& rng, int r, glm::vec3 center, float size, glm::vec3& origin,
                     glm::vec3& dir) {
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  origin = center + 2.0f * size * glm::vec3(unit(rng), unit(rng), unit(rng));
  glm::vec3 target = center + size * glm::vec3(unit(rng), unit(rng), unit(rng));
  if (!s.triangles.empty() && r % 4 != 3) {
    const Triangle& t = s.triangles[std::size_t(rng() % s.triangles.size())];
    float b1 = 0.5f * (unit(rng) + 1.0f), b2 = 0.5f * (unit(rng) + 1.0f);
    if (r % 5 == 0) b2 = 0.0f;             // on an edge
    if (r % 7 == 0) b1 = 0.0f, b2 = 0.0f;  // at a vertex
    if (b1 + b2 > 1.0f) b1 = 1.0f - b1, b2 = 1.0f - b2;
    target = (1.0f - b1 - b2) * t.p0 + b1 * t.p1 + b2 * t.p2;
  }
  dir = target - origin;
  if (r % 6 == 5) {  // along one axis: two direction components exactly zero
    int k = int(rng() % 3);
    origin = target, origin[k] += (r % 12 < 6 ? 1.5f : -1.5f) * size;
    dir = glm::vec3(0.0f), dir[k] = r % 12 < 6 ? -1.0f : 1.0f;
  }
}

std::vector<DegenerateScene> degenerate_scenes(std::mt19937& rng) {
  std::vector<DegenerateScene> scenes;
  Scene point;
  uint m = point.add_material(make_diffuse(glm::vec3(0.5f)));
  for (int i = 0; i < 200; i++) point.add_triangle({1, 2, 3}, {1, 2, 3}, {1, 2, 3}, m);
  point.add_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, m);  // something to hit
  scenes.push_back({"at one point", std::move(point), 500, 0});

  Scene one;
  one.add_material(make_diffuse(glm::vec3(0.5f)));
  one.add_triangle({-1, -1, 0}, {1, -1, 0}, {0, 1, 0}, 0u);
  scenes.push_back({"one triangle", std::move(one), 500, 0});

  Scene none;
  none.add_material(make_diffuse(glm::vec3(0.5f)));
  scenes.push_back({"no triangles", std::move(none), 50, 0});

  Scene copies;  // a grid of quads in one plane, every quad three times: ties everywhere
  add_copied_grid(copies, 12);
  scenes.push_back({"copies in a plane", std::move(copies), 2000, 100});

  Scene spread;  // triangles from 1e-6 to 1e6 in size, at distances to match
  add_spread_triangles(spread, rng, 600);
  scenes.push_back({"sizes 1e-6 to 1e6", std::move(spread), 3000, 0});
  return scenes;
}

}  // namespace pt::test
