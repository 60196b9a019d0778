// pt_bench's acceleration section on the CPU (accel.h): the renderer's own nearest-hit
// search, common/kernel/intersect.glsl and common/kernel/bvh.glsl compiled as C++ exactly
// as a stage's CPU kernel includes them (cpu/kernel_support.h: the BVH walk, or the brute
// force on SIMD lanes of cpu/triangle_lanes.h, by params.accel; the BVH as the CPU backend
// walks it, collapsed to 8 children on SIMD lanes, cpu/wide_bvh.h), and the two ray sets:
// camera rays (common/kernel/camera.glsl) and diffuse bounce rays from their hits, spawned
// by common/kernel/spawn.glsl.
#include <algorithm>
#include <cmath>
#include <random>

#include "bench/accel.h"
#include "cpu/kernel_prelude.h"

namespace {
namespace kernel {  // the renderer's intersection code, as a CPU kernel compiles it
#include "cpu/kernel_begin.h"
#include "common/kernel/camera.glsl"
#include "common/kernel/intersect.glsl"
#include "common/kernel/spawn.glsl"
#include "cpu/kernel_support.h"
}  // namespace kernel
}  // namespace

namespace pt::bench {

void bind_cpu_scene(const Scene& scene, const Bvh* bvh, const std::vector<float>* soa, uint soa_stride,
                    const WideBvh* wide) {
  kernel::triangles = scene.triangles.data();
  kernel::spheres = scene.spheres.data();
  kernel::params = FrameParams{};
  kernel::params.triangle_count = uint(scene.triangles.size());
  kernel::params.sphere_count = uint(scene.spheres.size());
  Bounds b = scene.bounds();  // as render.cpp sets it: the spawn offset scales with it
  kernel::params.scene_radius = b.empty() ? 1.0f : glm::max(0.5f * glm::length(b.hi - b.lo), 1e-30f);
  const bool has_bvh = bvh && !bvh->nodes.empty();
  kernel::bvh_nodes = has_bvh ? bvh->nodes.data() : nullptr;
  kernel::bvh_indices = has_bvh ? bvh->indices.data() : nullptr;
  kernel::wide_bvh = has_bvh && wide && wide->source == bvh->nodes.data() ? wide : nullptr;
  kernel::triangle_soa = soa ? soa->data() : nullptr;
  kernel::triangle_soa_stride = soa ? soa_stride : 0u;
}

namespace {

// The renderer's search for one ray: nearest_triangle() of cpu/triangle_lanes.h, which
// walks the BVH when params.accel says so and one was bound, else the SIMD brute force.
// t_max: the bound of a shadow ray (kernel::kInfinity: none).
kernel::Hit nearest(glm::vec3 origin, glm::vec3 dir, float t_max = kernel::kInfinity) {
  kernel::Ray ray(origin, dir);
  return kernel::nearest_triangle(ray, kernel::make_ray_shear(dir), kernel::Hit(t_max, 0.0f, 0.0f, 0u, kPrimNone));
}

}  // namespace

void set_cpu_accel(bool bvh) {
  kernel::params.accel = bvh ? kAccelBvh : kAccelNone;
}

void trace_cpu(const RaySet& rays, const std::size_t* index, std::size_t first, std::size_t last, float* t_out) {
  for (std::size_t k = first; k < last; k++) {
    const std::size_t i = index ? index[k] : k;
    if (rays.any_hit) {
      // occluded_triangles(), as occluded_scene() asks it in a scene without alpha masks (the
      // stages' kernels are specialised to the scene's features; this file's general kernel
      // would take occluded_scene()'s nearest-hit path for holes).
      const kernel::Ray ray(rays.origins[i], rays.dirs[i]);
      const bool blocked = kernel::occluded_triangles(ray, kernel::make_ray_shear(ray.dir), rays.bound(i));
      t_out[i] = blocked ? rays.bound(i) : kMiss;
      continue;
    }
    kernel::Hit h = nearest(rays.origins[i], rays.dirs[i], rays.bound(i));
    t_out[i] = h.kind == kPrimNone ? kMiss : h.t;
  }
}

RaySet camera_rays(const Camera& camera, int size, std::uint32_t seed) {
  RaySet r;
  const std::size_t n = std::size_t(size) * std::size_t(size);
  r.origins.reserve(n), r.dirs.reserve(n);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int y = 0; y < size; y++) {
    for (int x = 0; x < size; x++) {
      glm::vec2 film((float(x) + u(rng)) / float(size), (float(y) + u(rng)) / float(size));
      kernel::Ray ray = kernel::camera_ray(camera, film);
      r.origins.push_back(ray.origin), r.dirs.push_back(ray.dir);
    }
  }
  return r;
}

RaySet bounce_rays(const RaySet& camera, std::uint32_t seed) {
  RaySet r;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  kernel::params.accel = kernel::bvh_nodes ? kAccelBvh : kAccelNone;
  for (std::size_t i = 0; i < camera.size(); i++) {
    const float u1 = u(rng), u2 = u(rng);  // drawn for every ray: the same numbers per pixel
    kernel::Ray in(camera.origins[i], camera.dirs[i]);
    kernel::Hit hit = nearest(in.origin, in.dir);
    if (hit.kind == kPrimNone) continue;
    kernel::Surface s = kernel::surface_at(in, hit);
    const glm::vec3 n = s.front ? s.n : -s.n;  // the side the camera ray came from
    // Cosine-distributed about n (Malley: a uniform point of the disc, lifted to the
    // hemisphere), in a basis around n.
    const float radius = std::sqrt(u1), phi = 6.2831853f * u2;
    const glm::vec3 helper = std::fabs(n.x) > 0.5f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
    const glm::vec3 tx = glm::normalize(glm::cross(helper, n)), ty = glm::cross(n, tx);
    const glm::vec3 dir = glm::normalize(radius * std::cos(phi) * tx + radius * std::sin(phi) * ty +
                                         std::sqrt(std::max(0.0f, 1.0f - u1)) * n);
    kernel::Ray out = kernel::spawn_ray(s.p, s.n, dir);
    r.origins.push_back(out.origin), r.dirs.push_back(out.dir);
  }
  return r;
}

RaySet shadow_rays(const Scene& scene, const RaySet& camera, std::uint32_t seed) {
  // The emitting triangles and their cumulative areas, to pick a point uniformly by area.
  std::vector<std::size_t> lights;
  std::vector<double> cumulative;
  double total = 0.0;
  for (std::size_t t = 0; t < scene.triangles.size(); t++) {
    const Triangle& tri = scene.triangles[t];
    if (glm::dot(scene.materials[tri.material].emission, glm::vec3(1.0f)) <= 0.0f) continue;
    total += 0.5 * double(glm::length(glm::cross(tri.p1 - tri.p0, tri.p2 - tri.p0)));
    lights.push_back(t), cumulative.push_back(total);
  }
  RaySet r;
  if (lights.empty()) return r;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  kernel::params.accel = kernel::bvh_nodes ? kAccelBvh : kAccelNone;
  for (std::size_t i = 0; i < camera.size(); i++) {
    const float u0 = u(rng), u1 = u(rng), u2 = u(rng);  // drawn for every ray: the same numbers per pixel
    kernel::Ray in(camera.origins[i], camera.dirs[i]);
    kernel::Hit hit = nearest(in.origin, in.dir);
    if (hit.kind == kPrimNone) continue;
    kernel::Surface s = kernel::surface_at(in, hit);
    const glm::vec3 n = s.front ? s.n : -s.n;  // the side the camera ray came from
    const std::size_t pick = std::size_t(std::lower_bound(cumulative.begin(), cumulative.end(), double(u0) * total) -
                                         cumulative.begin());
    const Triangle& light = scene.triangles[lights[std::min(pick, lights.size() - 1)]];
    const float a = std::sqrt(u1);  // a uniform point of the triangle
    const glm::vec3 y = (1.0f - a) * light.p0 + a * (1.0f - u2) * light.p1 + a * u2 * light.p2;
    if (glm::dot(y - s.p, n) <= 0.0f) continue;  // behind the surface: light sampling skips it
    // As occluded() spawns it: off the surface, aimed at the light point itself; bounded
    // where occluded()'s last stretch begins (1e-4 of the length short of the light point), so
    // that no method counts the light's own surface, which Embree's inclusive tfar would.
    kernel::Ray out = kernel::spawn_ray(s.p, s.n, glm::normalize(y - s.p));
    const glm::vec3 to_light = y - out.origin;
    const float length_to_light = glm::length(to_light);
    r.origins.push_back(out.origin), r.dirs.push_back(to_light / length_to_light);
    r.t_max.push_back(length_to_light * (1.0f - 1e-4f));
  }
  return r;
}

}  // namespace pt::bench
