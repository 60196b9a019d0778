// pt_bench's stage section (issue 50): a stage program end to end on the 1.3 M-triangle
// builtin:furnace_mesh from several viewpoints, beside Embree 3 and the BVH's walk alone on
// exactly the rays the stage traces, and where a sample's time goes. Not part of the
// article: machinery for measuring the step after it (the BVH, docs/acceleration.md).
#pragma once

#include <sys/resource.h>

#include <vector>

#include "bench/accel.h"
#include "bench/bench.h"
#include "common/render/render.h"

namespace pt::bench {

// CPU seconds of the whole process so far (every thread, finished ones too): the measure on
// a machine that other jobs load.
inline double process_cpu_seconds() {
  rusage u;
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// The camera rays a stage's render of `s` traces, in its order (pass, row, pixel, sample).
RaySet stage_camera_rays(const Scene& scene, const RenderSettings& s);
// CPU seconds of making those rays alone (the sampler and camera_ray(), one thread).
double camera_ray_seconds(const Scene& scene, const RenderSettings& s);

// One ray a kernel traced: nearest hit closer than t_max, or any hit (shadow rays).
struct LoggedRay {
  glm::vec3 origin, dir;
  float t_max;
  bool any_hit;
};
// Every ray stage4 traces in its render of `s` (a recording copy of its kernel, one thread).
std::vector<LoggedRay> stage4_rays(const Scene& scene, const RenderSettings& s, const Bvh& bvh);

void run_accel_stage(const Config& config);

}  // namespace pt::bench
