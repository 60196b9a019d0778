// pt_bench's acceleration section (issue 17): rays per second of the nearest-hit search
// (shadow rays: bounded by their light point; and the any-hit search) against the triangle
// count, for the same rays, by the brute force (the article's search, Eq. 2, as the CPU
// kernel compiles it), this project's BVH on the CPU and on the GPU
// backend (gpu/bvh_walk.glsl), and Embree 3 when the build found it; and the BVH's
// build time and size against Embree's high-quality build. What its parts share.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "common/kernel/scene_types.h"
#include "common/scene/bvh.h"
#include "common/scene/scene.h"
#include "cpu/wide_bvh.h"

namespace pt::bench {

struct Config;

// The cores the CPU methods run on (all of them), and a number with `digits` decimals.
unsigned cores();
std::string fixed(double v, int digits);

// The build of `scene` three times each by build_bvh and by Embree's high-quality build,
// on all cores and on one: accel_build.csv and a table on stdout (accel_build.cpp).
void compare_builds(const Scene& scene, const Config& config);

// The measured scenes: level < 0 is builtin:cornell (36 triangles); level >= 0 the Cornell
// room (its 12 triangles of walls and light) with an icosphere of 20 * 4^level triangles in
// place of the two boxes (accel_scene.cpp), as bench/make_sphere_mesh.py places it.
Scene accel_scene(int level);
std::string accel_scene_name(int level);
// The pinhole camera of both ray sets: it frames the sphere, the room around it.
Camera accel_camera();

constexpr float kNoBound = 3.402823466e38f;  // the largest float, intersect.glsl's kInfinity

// A ray set in two arrays (unit directions), and for shadow rays each ray's bound: the
// search then finds the nearest hit closer than it, as the renderer's occluded() asks
// (common/kernel/lights.glsl); empty: none, the largest float (intersect.glsl's kInfinity).
// any_hit: the search asks only whether something lies closer than the bound (the any-hit
// walk, occluded_triangles(): shadow rays towards the sky and the sun), and a
// blocked ray's distance is reported as its bound.
struct RaySet {
  std::vector<glm::vec3> origins;
  std::vector<glm::vec3> dirs;
  std::vector<float> t_max;
  bool any_hit = false;
  std::size_t size() const { return origins.size(); }
  float bound(std::size_t i) const { return t_max.empty() ? kNoBound : t_max[i]; }
};

// The nearest-hit distance of a ray, +infinity for a miss.
constexpr float kMiss = __builtin_inff();

// The CPU kernel's search (accel_cpu.cpp): common/kernel/intersect.glsl and bvh.glsl
// compiled as C++ with cpu/triangle_lanes.h, as the stages' CPU kernels compile them.
// Binds the scene to the kernel's globals: its BVH (nullptr: none) and its triangles as
// arrays for the brute force's SIMD lanes (nullptr: none).
// wide: the same tree collapsed for the CPU backend's SIMD walk (cpu/wide_bvh.h), which the
// search then takes instead of the binary walk, as the CPU backend does.
void bind_cpu_scene(const Scene& scene, const Bvh* bvh, const std::vector<float>* soa, uint soa_stride,
                    const WideBvh* wide = nullptr);
// How trace_cpu() searches: through the BVH (--accel bvh) or by the brute force (--accel
// none), as params.accel tells nearest_triangle(). Set before the threads start.
void set_cpu_accel(bool bvh);
// t_out[i] for the rays i = index[k], k in [first, last) (index nullptr: i = k): the
// distance of the nearest hit (closer than the ray's bound) as nearest_triangle() finds it,
// or kMiss; for an any-hit set, the bound where occluded_triangles() says blocked. Thread-safe.
void trace_cpu(const RaySet& rays, const std::size_t* index, std::size_t first, std::size_t last, float* t_out);
// size x size camera rays, one through a random point of each pixel, row by row.
RaySet camera_rays(const Camera& camera, int size, std::uint32_t seed);
// From each camera ray's hit (through the bound BVH), one ray cosine-distributed about the
// surface normal on the side the camera ray came from, spawned as the renderer spawns it
// (common/kernel/spawn.glsl); rays that missed give none.
RaySet bounce_rays(const RaySet& camera, std::uint32_t seed);
// From each camera ray's hit, a shadow ray to a uniformly chosen point of the scene's
// emitting triangles (the room's ceiling light), spawned as the renderer's occluded() spawns
// it (common/kernel/lights.glsl) and bounded where occluded()'s last stretch before the light
// point begins: a search for the nearest hit closer than that. Hits whose light point lies
// behind the surface give none, as light sampling skips them.
RaySet shadow_rays(const Scene& scene, const RaySet& camera, std::uint32_t seed);

// Embree 3 (accel_embree.cpp): a scene of one triangle mesh, built with
// RTC_BUILD_QUALITY_HIGH on `threads` threads, traced by rtcIntersect1 one ray at a time.
class EmbreeScene {
 public:
  // Whether the build found Embree; if not, why in one line.
  static bool available();
  static std::string missing_reason();
  static std::string version();

  EmbreeScene(std::span<const Triangle> triangles, unsigned build_threads);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  double build_seconds() const { return build_seconds_; }  // rtcNewScene .. rtcCommitScene
  double commit_seconds() const { return commit_seconds_; }  // rtcCommitScene alone
  std::size_t bytes() const { return bytes_; }  // what the commit allocated and kept
  // t_out[i] for rays [first, first + n): the nearest hit's distance (closer than the ray's
  // bound: rtcIntersect1's tfar), or kMiss; for an any-hit set rtcOccluded1, the bound where
  // blocked. Thread-safe.
  void trace(const RaySet& rays, std::size_t first, std::size_t n, float* t_out) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  double build_seconds_ = 0.0, commit_seconds_ = 0.0;
  std::size_t bytes_ = 0;
};

// The GPU's BVH walk (gpu/bvh_walk.glsl) on the default Vulkan device (accel_gpu.cpp):
// one invocation per ray of a buffer, as the renderer's kernels search with --accel bvh.
class GpuBvhTracer {
 public:
  // Throws pt::Error(kExitNoDevice) when there is no Vulkan device.
  GpuBvhTracer();
  ~GpuBvhTracer();
  std::string device() const;
  // Uploads the triangles, the BVH and the rays, and makes the pipeline.
  void set_scene(const Scene& scene, const Bvh& bvh, const RaySet& rays);
  // One dispatch over every ray; the first after set_scene() is a warm-up and not counted.
  void run();
  double wall() const;  // seconds of the counted dispatches
  double cpu() const;   // process CPU seconds of them
  std::uint64_t runs() const;
  // The distances of the last dispatch (kMiss for a miss).
  std::vector<float> distances() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pt::bench
