// The tessellated sphere of the BVH's large-scene tests and builtin:furnace_mesh
// (add_icosphere, common/scene/scene_shapes.cpp): its count, its closure and its orientation.
// A closed surface is what makes the furnace's closed form hold for the mesh.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <map>

#include "common/scene/scene.h"

using namespace pt;

namespace {

using Vertex = std::array<float, 3>;
Vertex key(glm::vec3 p) { return {p.x, p.y, p.z}; }

}  // namespace

TEST_CASE("add_icosphere: 20 n^2 triangles on the sphere, every edge shared by two of them in opposite directions",
          "[scene][bvh]") {
  for (int n : {1, 2, 3, 7, 16}) {
    for (bool inward : {false, true}) {
      Scene s;
      const glm::vec3 center(0.25f, -3.0f, 1e3f);
      const float radius = 2.5f;
      add_icosphere(s, center, radius, n, s.add_material(make_diffuse(glm::vec3(0.5f))), inward);
      INFO("n = " << n << (inward ? ", inward" : ", outward"));
      REQUIRE(s.triangles.size() == std::size_t(20 * n * n));
      // Directed edges as exact float triples: a watertight closed surface has each one
      // once, and its reverse once.
      std::map<std::pair<Vertex, Vertex>, int> edges;
      int wrong_side = 0;
      for (const Triangle& t : s.triangles) {
        const glm::vec3 p[3] = {t.p0, t.p1, t.p2};
        for (int i = 0; i < 3; i++) {
          edges[{key(p[i]), key(p[(i + 1) % 3])}]++;
          CHECK(std::abs(glm::length(p[i] - center) - radius) <= 1e-5f * 1e3f);
        }
        const glm::vec3 normal = glm::cross(t.p1 - t.p0, t.p2 - t.p0);
        const bool outwards = glm::dot(normal, (t.p0 + t.p1 + t.p2) / 3.0f - center) > 0.0f;
        wrong_side += outwards == inward;
      }
      CHECK(wrong_side == 0);
      int unmatched = 0;
      for (const auto& [edge, count] : edges) {
        auto reverse = edges.find({edge.second, edge.first});
        unmatched += count != 1 || reverse == edges.end() || reverse->second != 1;
      }
      CHECK(unmatched == 0);
      CHECK(edges.size() == 3 * s.triangles.size());
    }
  }
}
