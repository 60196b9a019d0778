// pt_bench's stage section (issue 50): the rays a stage traces, for Embree and the walk alone:
// camera rays as render_pixel() makes them, and every ray of stage4, recorded by a copy of its
// kernel built here with cpu/triangle_lanes.h's PT_CPU_RAY_LOG hook (the stages have none).
// Not part of the article: machinery for measuring the step after it (the BVH).
#include <cmath>

#include "bench/accel_stage.h"
#include "common/render/render.h"
#include "cpu/cpu_backend.h"
#include "cpu/kernel_prelude.h"

namespace pt::bench {
namespace {
std::vector<LoggedRay>* g_log = nullptr;  // where the recording kernel writes (one thread)
}  // namespace
void log_ray(glm::vec3 origin, glm::vec3 dir, float t_max, bool any_hit) {
  if (g_log) g_log->push_back(LoggedRay{origin, dir, t_max, any_hit});
}
}  // namespace pt::bench

#define PT_CPU_RAY_LOG(ray, t_max, any_hit) ::pt::bench::log_ray(ray.origin, ray.dir, t_max, any_hit)
namespace bench_stage4_log {  // stage4's integrator, every ray recorded (the general kernel)
#include "cpu/kernel_begin.h"
#include "stage4_direct_indirect/integrator.glsl"
#include "cpu/kernel_end.h"
}  // namespace bench_stage4_log
#undef PT_CPU_RAY_LOG

namespace pt::bench {

RaySet stage_camera_rays(const Scene& scene, const RenderSettings& s) {
  using namespace bench_stage4_log;
  const FrameParams p = make_frame_params(scene, s);
  params = p;
  RaySet r;
  const std::size_t n = std::size_t(s.width) * std::size_t(s.height) * s.spp;
  r.origins.reserve(n), r.dirs.reserve(n);
  // The passes of render(): samples [first, pass_end(first)) of every pixel, row by row.
  for (std::uint64_t first = 0; first < s.spp; first = std::min<std::uint64_t>(pass_end(first), s.spp)) {
    const std::uint64_t end = std::min<std::uint64_t>(pass_end(first), s.spp);
    for (uint y = 0; y < p.height; y++) {
      for (uint x = 0; x < p.width; x++) {
        for (std::uint64_t k = first; k < end; k++) {
          start_sample(y * p.width + x, uint(k), p.seed, p.sampler_kind);
          vec2 jitter = sample_2d();
          Ray ray = camera_ray(p.camera, vec2((float(x) + jitter.x) / float(p.width),
                                              (float(y) + jitter.y) / float(p.height)));
          r.origins.push_back(ray.origin), r.dirs.push_back(ray.dir);
        }
      }
    }
  }
  return r;
}

double camera_ray_seconds(const Scene& scene, const RenderSettings& s) {
  using namespace bench_stage4_log;
  const FrameParams p = make_frame_params(scene, s);
  params = p;
  const double t0 = process_cpu_seconds();
  float sum = 0.0f;
  for (uint y = 0; y < p.height; y++) {
    for (uint x = 0; x < p.width; x++) {
      for (uint k = 0; k < uint(s.spp); k++) {
        start_sample(y * p.width + x, k, p.seed, p.sampler_kind);
        vec2 jitter = sample_2d();
        sum += camera_ray(p.camera, vec2((float(x) + jitter.x) / float(p.width), (float(y) + jitter.y) / float(p.height)))
                   .dir.x;
      }
    }
  }
  const double t = process_cpu_seconds() - t0;
  return sum == 1234.5f ? t + 1e-12 : t;  // the sum keeps the work alive
}

std::vector<LoggedRay> stage4_rays(const Scene& scene, const RenderSettings& s, const Bvh& bvh) {
  static const CpuKernel kernel[] = {bench_stage4_log::cpu_kernel()};
  StageKernels k{"stage4_log", kernel, {}, true};
  std::unique_ptr<Backend> backend = make_cpu_backend(k, 1);
  std::vector<LoggedRay> log;
  log.reserve(std::size_t(s.width) * std::size_t(s.height) * s.spp * 4u);
  g_log = &log;
  RenderHooks h;
  h.bvh = &bvh;
  render(*backend, scene, s, h);
  g_log = nullptr;
  return log;
}

}  // namespace pt::bench
