// pt_bench, the speed-versus-accuracy lab (issue 6): what its sections share. The article's
// stages differ in their estimator (Eq. 3 uniform sampling, importance sampling, direct +
// indirect light); the bench measures what each costs and gives, per scene and backend.
#pragma once

#include <cstdint>
#include <ctime>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "common/render/backend.h"
#include "common/render/render.h"
#include "common/scene/scene.h"

namespace pt::bench {

// CPU seconds of the calling thread so far: what a worker of a timed race spent, whatever
// else the machine runs.
inline double thread_cpu_seconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

struct Config {
  int size = 64;                     // images are size x size
  double seconds = 4.0;              // per run of the error study: the last checkpoint starts before this
  double reference_seconds = 60.0;   // a cached reference renders this long (stage4, CPU)
  std::string cache_dir = "build/bench_cache";
  std::string out_dir = "docs/results";
  std::uint32_t seed = 1;
  // The error study's Russian roulette for every stage: kRouletteThroughput (--rr throughput,
  // the default of stages 3 to 5; stage5 reads its square root), or kRouletteFixed, the
  // article's p = 1/2 (stage2's default).
  std::uint32_t roulette = kRouletteThroughput;
  // The acceleration section (issue 17, accel.cpp).
  int accel_size = 512;              // camera rays: accel_size x accel_size
  int accel_max_level = 8;           // the largest icosphere: 20 * 4^level triangles
  double accel_seconds = 0.5;        // per method, scene and ray set
  double accel_brute_limit = 3.0;    // the brute force skips a count it would spend longer on
  // The stage section (issue 50, accel_stage.cpp): stage1 at stage_size^2 x 16 spp, stage4 at
  // half that size, each `stage_rounds` times alternating with Embree on the same rays.
  int stage_size = 256;
  int stage_rounds = 3;
  std::vector<std::string> stage_views;  // only these "stage:view" rows (e.g. stage1:inside); empty: all
  std::string command;               // the command line, for the record (accel_run.txt)
};

// One line of the run list: a scene, a stage, a backend.
struct Run {
  std::string scene;    // builtin NAME or a glTF path
  std::string stage;    // stage1_raycast ... stage6_variance_aware
  std::string backend;  // cpu or gpu
};

// The stage's kernels by program name or by its number ("2"); throws Error(2) if unknown.
StageKernels stage_kernels(const std::string& stage);
std::string stage_name(const std::string& stage);

// One backend per (stage, kind), made on first use: the GPU keeps its pipelines.
Backend& backend_for(const std::string& stage, const std::string& kind);

// builtin:NAME for a bare name, the path otherwise.
Scene load_bench_scene(const std::string& scene);

// A rate by the wall clock and by CPU time (all the process's threads, also lavapipe's,
// times the cores): on a shared machine the second is the steadier measure.
struct Rate {
  double wall = 0.0;
  double cpu = 0.0;
};

// Samples per second of one render of `s` (width x height x spp samples).
Rate samples_per_second(Backend& backend, const Scene& scene, const RenderSettings& s);

// The CSV file NAME in --out (its folder made), or Error(kExitOutput) naming it.
std::ofstream open_csv(const Config& config, const std::string& name);

// The scene's true image (linear RGB, row-major from the top) and where it came from:
// the closed form for the analytic scenes, else a converged render cached on disk.
struct Reference {
  std::vector<float> rgb;
  std::string source;            // "closed form" or "stage4 cpu, N spp"
  double relative_error = 0.0;   // the reference's own estimated relative RMSE per pixel
};
Reference reference_image(const std::string& scene, const Config& config);

// Error of an image against the reference, by OpenImageIO's ImageBufAlgo::compare.
struct ErrorMetrics {
  double rmse = 0.0;      // over pixels and channels
  double relative = 0.0;  // rmse / mean of the reference
};
ErrorMetrics compare_images(const std::vector<float>& image, const Reference& reference, int size);

// The sections; each writes a CSV into config.out_dir and a short table on stdout.
void run_error_study(const std::vector<Run>& runs, const Config& config);
void run_speed(const Config& config);
void run_accel(const Config& config);
void run_accel_stage(const Config& config);
void run_specialisation(const std::vector<std::string>& stages, const std::vector<std::string>& backends,
                        const Config& config);

}  // namespace pt::bench
