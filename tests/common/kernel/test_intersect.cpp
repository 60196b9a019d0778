// The intersection routines of common/kernel/intersect.glsl, compiled here as C++ as the
// CPU kernels compile them: watertight triangles (rays aimed at shared edges and vertices
// of a closed mesh never pass through it) and spheres hit from outside and inside.
#include <catch2/catch.hpp>

#include <random>

#include "common/scene/scene.h"
#include "cpu/kernel_prelude.h"

namespace {  // internal linkage: each test file compiles its own copy of the kernel code
namespace kernel {
#include "cpu/kernel_begin.h"
#include "common/kernel/camera.glsl"
#include "common/kernel/intersect.glsl"
#include "cpu/kernel_support.h"
}  // namespace kernel
}  // namespace

namespace {

// An octahedron's eight faces around `center`, outward facing, with shared edges.
pt::Scene octahedron(glm::vec3 center, float r) {
  pt::Scene s;
  uint m = s.add_material(pt::make_diffuse(glm::vec3(0.5f)));
  glm::vec3 px = center + glm::vec3(r, 0, 0), nx = center + glm::vec3(-r, 0, 0);
  glm::vec3 py = center + glm::vec3(0, r, 0), ny = center + glm::vec3(0, -r, 0);
  glm::vec3 pz = center + glm::vec3(0, 0, r), nz = center + glm::vec3(0, 0, -r);
  s.add_triangle(px, py, pz, m), s.add_triangle(py, nx, pz, m), s.add_triangle(nx, ny, pz, m);
  s.add_triangle(ny, px, pz, m), s.add_triangle(py, px, nz, m), s.add_triangle(nx, py, nz, m);
  s.add_triangle(ny, nx, nz, m), s.add_triangle(px, ny, nz, m);
  return s;
}

void bind(const pt::Scene& s) {
  kernel::triangles = s.triangles.data();
  kernel::spheres = s.spheres.data();
  kernel::params.triangle_count = uint(s.triangles.size());
  kernel::params.sphere_count = uint(s.spheres.size());
}

}  // namespace

TEST_CASE("intersect: rays aimed at shared edges and vertices of a closed mesh never pass through",
          "[intersect][stability]") {
  // Away from the origin, where rounding is coarser than the mesh's own numbers.
  const glm::vec3 center(1013.7f, -507.3f, 251.1f);
  pt::Scene s = octahedron(center, 1.3f);
  bind(s);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  int misses_outside = 0, escapes_inside = 0;
  const int kRays = 20000;
  for (int i = 0; i < kRays; i++) {
    // A target on an edge (or at a vertex, every fourth ray).
    const pt::Triangle& t = s.triangles[i % s.triangles.size()];
    float a = (i % 4 == 0) ? 0.0f : u(rng);
    glm::vec3 target = glm::mix(t.p0, t.p1, a);
    // A ray through the target towards a point inside enters the mesh exactly at the edge
    // or vertex: from outside it must hit, and from inside it must not escape.
    glm::vec3 inner = center + 0.5f * glm::vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f);
    glm::vec3 dir = glm::normalize(inner - target);
    kernel::Hit h = kernel::intersect_scene(kernel::Ray(target - 5.0f * dir, dir), kernel::kInfinity);
    misses_outside += h.kind == pt::kPrimNone;
    kernel::Hit h2 = kernel::intersect_scene(kernel::Ray(inner, -dir), kernel::kInfinity);
    escapes_inside += h2.kind == pt::kPrimNone;
  }
  CHECK(misses_outside == 0);
  CHECK(escapes_inside == 0);
}

TEST_CASE("intersect: the nearest hit wins and reports its barycentrics", "[intersect]") {
  pt::Scene s;
  uint m = s.add_material(pt::make_diffuse(glm::vec3(0.5f)));
  s.add_triangle({-1, -1, -2}, {1, -1, -2}, {-1, 1, -2}, m);  // behind
  s.add_triangle({-1, -1, -1}, {1, -1, -1}, {-1, 1, -1}, m);  // in front
  bind(s);
  kernel::Hit h = kernel::intersect_scene(kernel::Ray(glm::vec3(-0.5f, -0.25f, 0.0f), glm::vec3(0, 0, -1)),
                                          kernel::kInfinity);
  REQUIRE(h.kind == pt::kPrimTriangle);
  CHECK(h.prim == 1u);
  CHECK(h.t == Approx(1.0f));
  // p = (1 - b1 - b2) p0 + b1 p1 + b2 p2 with p = (-0.5, -0.25): b1 = 0.25, b2 = 0.375.
  CHECK(h.b1 == Approx(0.25f));
  CHECK(h.b2 == Approx(0.375f));
  kernel::Surface surf = kernel::surface_at(kernel::Ray(glm::vec3(-0.5f, -0.25f, 0.0f), glm::vec3(0, 0, -1)), h);
  CHECK(surf.front);
  CHECK(surf.n.z == Approx(1.0f));
  CHECK(surf.p.x == Approx(-0.5f));
  CHECK(surf.p.y == Approx(-0.25f));
}

TEST_CASE("intersect: spheres are hit from outside and from inside", "[intersect]") {
  pt::Scene s;
  uint m = s.add_material(pt::make_diffuse(glm::vec3(0.5f)));
  s.add_sphere({0, 0, -5}, 2.0f, m);
  bind(s);
  kernel::Ray outside(glm::vec3(0.0f), glm::vec3(0, 0, -1));
  kernel::Hit h = kernel::intersect_scene(outside, kernel::kInfinity);
  REQUIRE(h.kind == pt::kPrimSphere);
  CHECK(h.t == Approx(3.0f));
  CHECK(kernel::surface_at(outside, h).front);
  kernel::Ray inside(glm::vec3(0, 0, -5), glm::vec3(1, 0, 0));
  kernel::Hit h2 = kernel::intersect_scene(inside, kernel::kInfinity);
  REQUIRE(h2.kind == pt::kPrimSphere);
  CHECK(h2.t == Approx(2.0f));
  CHECK_FALSE(kernel::surface_at(inside, h2).front);
  // A ray that passes beside it, and one pointing away, miss.
  CHECK(kernel::intersect_scene(kernel::Ray(glm::vec3(0, 2.01f, 0), glm::vec3(0, 0, -1)), kernel::kInfinity).kind ==
        pt::kPrimNone);
  CHECK(kernel::intersect_scene(kernel::Ray(glm::vec3(0.0f), glm::vec3(0, 0, 1)), kernel::kInfinity).kind ==
        pt::kPrimNone);
}
