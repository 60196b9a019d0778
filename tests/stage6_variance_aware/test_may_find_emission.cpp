// may_find_emission (stage6_variance_aware/roulette_after_emission.glsl; beyond the article),
// compiled as the CPU kernels compile it: a path the roulette ended traces its last ray only
// where it says that ray might find emission, so it must say so for every ray whose nearest
// hit emits (or that reaches a lit sky), and say no often enough to save rays.
#include <catch2/catch.hpp>

#include <cstdio>
#include <random>
#include <string>

#include "common/scene/scene.h"
#include "common/scene/scene_loading.h"
#include "cpu/kernel_prelude.h"
#include "tests/support/test_render.h"

namespace {  // internal linkage: each test file compiles its own copy of the kernel code
namespace kernel {
// The kernel copy of a scene without alpha masks: the one in which the shortcut is on.
#define PT_CPU_FEATURES (kFeatureAll & ~kFeatureAlphaMask)
#include "tests/support/light_kernel.h"
#include "stage6_variance_aware/roulette_after_emission.glsl"
#undef PT_CPU_FEATURES
}  // namespace kernel

struct Counts {
  int rays = 0;
  int emitting = 0;  // rays whose nearest hit emits (or that reach a lit sky)
  int skipped = 0;   // rays may_find_emission answers false for
  int dropped = 0;   // emitting rays it answers false for: must stay 0
};

// Whether tracing `ray` in full finds emission, as stage6's loop counts it.
bool finds_emission(const kernel::Ray& ray, glm::vec3 sky) {
  kernel::Hit hit = kernel::intersect_scene(ray, kernel::kInfinity);
  if (hit.kind == kernel::kPrimNone) return sky.x > 0.0f || sky.y > 0.0f || sky.z > 0.0f;
  kernel::Surface surface = kernel::surface_at(ray, hit);
  glm::vec3 le = kernel::emitted_radiance(kernel::surface_material(surface), surface.front);
  return le.x > 0.0f || le.y > 0.0f || le.z > 0.0f;
}

void check(const kernel::Ray& ray, glm::vec3 sky, Counts& c) {
  bool emits = finds_emission(ray, sky);
  bool may = kernel::may_find_emission(ray);
  c.rays++;
  c.emitting += emits;
  c.skipped += !may;
  if (emits && !may && c.dropped++ < 3) {
    std::printf("dropped: origin (%.9g, %.9g, %.9g) dir (%.9g, %.9g, %.9g)\n", ray.origin.x, ray.origin.y,
                ray.origin.z, ray.dir.x, ray.dir.y, ray.dir.z);
  }
}

glm::vec3 uniform_direction(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  float z = 1.0f - 2.0f * u(rng);
  float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  float phi = 6.2831853f * u(rng);
  return glm::vec3(r * std::cos(phi), r * std::sin(phi), z);
}

// A point on light `index` of the table: inside a triangle, on one of its edges, at a
// corner, or on a sphere light's surface.
glm::vec3 point_on_light(const pt::Scene& s, uint index, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const pt::Light& l = s.lights[index];
  if (l.kind == pt::kLightSphere) {
    const pt::Sphere& sp = s.spheres[l.index];
    return sp.center + sp.radius * uniform_direction(rng);
  }
  const pt::Triangle& t = s.triangles[l.index];
  float b1 = u(rng), b2 = u(rng);
  if (b1 + b2 > 1.0f) b1 = 1.0f - b1, b2 = 1.0f - b2;
  switch (rng() % 4u) {
    case 0: b1 = 0.0f; break;              // the edge p0 p2
    case 1: b2 = 1.0f - b1; break;         // the edge p1 p2
    case 2: b1 = float(rng() % 2u), b2 = 0.0f; break;  // a corner
    default: break;                        // inside
  }
  return (1.0f - b1 - b2) * t.p0 + b1 * t.p1 + b2 * t.p2;
}

Counts run(const std::string& name, glm::vec3 sky, std::uint32_t seed) {
  pt::Scene s = pt::load_scene(name);
  kernel::bind_scene(s, sky);
  kernel::params.scene_radius = 0.5f * glm::length(s.bounds().hi - s.bounds().lo);
  std::mt19937 rng(pt::test::test_seed(seed));
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const pt::Bounds b = s.bounds();
  Counts c;
  for (int i = 0; i < 20000; i++) {
    glm::vec3 o = b.lo + glm::vec3(u(rng), u(rng), u(rng)) * (b.hi - b.lo);
    // A random ray through the scene.
    kernel::Ray ray{o, uniform_direction(rng)};
    check(ray, sky, c);
    // A ray aimed at a point of a light: its edges and corners are where two searches of
    // the same triangle could disagree, if they differed at all.
    if (!s.lights.empty() && s.lights[0].kind != pt::kLightPoint) {
      uint light = uint(rng() % s.lights.size());
      if (s.lights[light].kind != pt::kLightPoint) {
        glm::vec3 to = point_on_light(s, light, rng) - o;
        if (glm::length(to) > 0.0f) check(kernel::Ray{o, glm::normalize(to)}, sky, c);
      }
    }
    // A ray leaving the surface the first one hit, as a path's next ray does.
    kernel::Hit hit = kernel::intersect_scene(ray, kernel::kInfinity);
    if (hit.kind != kernel::kPrimNone) {
      kernel::Surface surface = kernel::surface_at(ray, hit);
      glm::vec3 n = surface.front ? surface.n : -surface.n;
      glm::vec3 d = uniform_direction(rng);
      if (glm::dot(d, n) < 0.0f) d = -d;
      check(kernel::spawn_ray(surface.p, surface.n, d), sky, c);
    }
  }
  std::printf("%s: %d rays, %d find emission, %d skipped, %d dropped\n", name.c_str(), c.rays, c.emitting, c.skipped,
              c.dropped);
  return c;
}
}  // namespace

TEST_CASE("may_find_emission: no ray whose nearest hit emits is skipped, and rays that find none are",
          "[stage6]") {
  const std::string scenes[] = {"builtin:cornell", "builtin:smallpt", "builtin:every_feature", "builtin:furnace",
                                "builtin:floor_small_light", "builtin:furnace_sphere"};
  std::uint32_t seed = 41;
  for (const std::string& name : scenes) {
    Counts c = run(name, glm::vec3(0.0f), seed++);
    INFO(name);
    CHECK(c.dropped == 0);
    CHECK(c.emitting > 0);
    // The shortcut works where it is meant to: in the Cornell box (one small light) most
    // rays meet no light. (In the box furnace every wall emits: only a ray from a corner
    // that leaves the box may be skipped.)
    if (name == "builtin:cornell") CHECK(c.skipped > c.rays / 2);
  }
}

TEST_CASE("may_find_emission: under a lit sky every ray is traced", "[stage6]") {
  Counts c = run("builtin:every_feature", glm::vec3(0.3f, 0.4f, 0.5f), 57);
  CHECK(c.skipped == 0);
  CHECK(c.dropped == 0);
}
