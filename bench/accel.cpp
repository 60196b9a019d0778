// pt_bench's acceleration section (issue 17; accel.h): rays per second of the nearest-hit
// search against the triangle count, from builtin:cornell's 36 triangles to a 1.3-million
// triangle icosphere in the Cornell room, for the same camera rays, diffuse bounce rays
// and shadow rays (bounded by the light point, as stages 4 and 5 trace them; and the same
// shadow rays through the any-hit search, as rays towards the sky and the sun go) in the
// same run: the brute force (the article's search, Eq. 2, as the CPU kernel compiles it), the BVH on the CPU and on the GPU backend, and Embree 3. The CPU methods run on
// all cores, alternating, so that they see the same load. Then the build of the largest
// mesh: build_bvh against Embree's high-quality build (accel_build.cpp). Writes
// docs/results/accel.csv, accel_build.csv and accel_run.txt (the command, the date and
// the machine's load).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <optional>
#include <sstream>
#include <thread>
#include <utility>

#include "bench/accel.h"
#include "bench/accel_race.h"
#include "bench/bench.h"
#include "common/base/error.h"
#include "cpu/triangle_soa.h"

namespace pt::bench {

unsigned cores() {
  return std::max(1u, std::thread::hardware_concurrency());
}

std::string fixed(double v, int digits) {
  char s[64];
  std::snprintf(s, sizeof s, "%.*f", digits, v);
  return s;
}

namespace {

using Clock = std::chrono::steady_clock;

constexpr std::size_t kMinBruteRays = 2048;  // fewer would say little; skip the count instead

// The CPU's model name (/proc/cpuinfo), for the run file: a section re-run alone may run
// on another machine than the rest of the results.
std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos) {
      std::string name = line.substr(line.find(':') + 1);
      name.erase(0, name.find_first_not_of(" \t"));
      return name;
    }
  }
  return "unknown";
}

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string a, b, c;
  in >> a >> b >> c;
  return in ? a + " " + b + " " + c : "unknown";
}

}  // namespace

void run_accel(const Config& config) {
  const std::string load_before = load_average();
  const Clock::time_point start = Clock::now();
  const std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  if (!EmbreeScene::available()) std::printf("embree: %s; the Embree column stays empty\n", EmbreeScene::missing_reason().c_str());
  std::optional<GpuBvhTracer> gpu;
  try {
    gpu.emplace();
  } catch (const Error& e) {
    std::printf("gpu: %s (no GPU column)\n", e.what());
  }
  const RaySet camera = camera_rays(accel_camera(), config.accel_size, config.seed);
  Csv csv{open_csv(config, "accel.csv")};
  csv.out << "rays,level,triangles,method,device,threads,rays_timed,passes,mrays_per_s,mrays_per_cpu_s,rays_checked,"
             "hits,mean_t,rays_differing_from_bvh_cpu,note\n";
  std::vector<int> levels{-1};
  for (int l = 1; l <= config.accel_max_level; l++) levels.push_back(l);
  double brute_tests_per_s[4] = {0.0, 0.0, 0.0, 0.0};  // triangle tests per second of the last brute force, per set
  const std::string cpu_device = std::to_string(cores()) + " threads";
  for (int level : levels) {
    Scene scene = accel_scene(level);
    const std::size_t n = scene.triangles.size();
    Bvh bvh = build_bvh(scene.triangles);
    Clock::time_point wide_start = Clock::now();
    const WideBvh wide = build_wide_bvh(bvh, scene.triangles);  // as the CPU backend's set_scene builds it
    const double wide_seconds = seconds_since(wide_start);
    bind_cpu_scene(scene, &bvh, nullptr, 0, &wide);
    const RaySet bounce = bounce_rays(camera, config.seed + 1u + uint(level + 1));
    const RaySet shadow = shadow_rays(scene, camera, config.seed + 101u + uint(level + 1));
    RaySet occlusion = shadow;  // the same rays through the any-hit search
    occlusion.any_hit = true;
    std::printf("== %s: %zu triangles, BVH %s; %zu camera rays, %zu bounce rays, %zu shadow rays\n",
                accel_scene_name(level).c_str(), n, bvh.stats.summary().c_str(), camera.size(), bounce.size(),
                shadow.size());
    std::printf("   CPU's wide tree: %zu nodes, %zu leaf blocks, %.1f ms\n", wide.nodes.size(), wide.blocks.size(),
                1e3 * wide_seconds);
    std::optional<EmbreeScene> embree;
    if (EmbreeScene::available()) embree.emplace(scene.triangles, cores());
    std::optional<TriangleSoa> soa;
    for (int set = 0; set < 4; set++) {
      const RaySet& rays = set == 0 ? camera : set == 1 ? bounce : set == 2 ? shadow : occlusion;
      const char* set_name = set == 0 ? "camera" : set == 1 ? "bounce" : set == 2 ? "shadow" : "shadow_any";
      Result bvh_cpu{"bvh_cpu", cpu_device}, brute{"brute_cpu", cpu_device}, emb{"embree", cpu_device},
          bvh_gpu{"bvh_gpu", gpu ? gpu->device() : ""};
      auto trace = [&](const std::size_t* index, std::size_t a, std::size_t b, float* t) { trace_cpu(rays, index, a, b, t); };
      bvh_cpu.pass = cpu_pass(bvh_cpu, rays, [&] { bind_cpu_scene(scene, &bvh, nullptr, 0, &wide), set_cpu_accel(true); }, trace);
      std::vector<Result*> racers{&bvh_cpu};
      if (embree) {
        emb.device = EmbreeScene::version() + ", " + cpu_device;
        emb.pass = cpu_pass(emb, rays, [] {}, [&](const std::size_t*, std::size_t a, std::size_t b, float* t) {
          embree->trace(rays, a, b - a, t);
        });
        racers.push_back(&emb);
      } else {
        emb.note = EmbreeScene::missing_reason();
      }
      if (gpu) {
        try {
          gpu->set_scene(scene, bvh, rays);
          bvh_gpu.pass = [&](bool) {
            gpu->run();
            bvh_gpu.wall = gpu->wall(), bvh_gpu.cpu = gpu->cpu(), bvh_gpu.passes = gpu->runs();
            bvh_gpu.rays = bvh_gpu.passes * rays.size();
          };
          racers.push_back(&bvh_gpu);
        } catch (const Error& e) {
          bvh_gpu.note = e.what();
        }
      } else {
        bvh_gpu.note = "no Vulkan device";
      }
      // The brute force: all the rays when a pass is short, else an even sample of them
      // (every k-th), or none when even kMinBruteRays would take too long.
      const double predicted = brute_tests_per_s[set] > 0.0 ? brute_tests_per_s[set] / double(n) : 0.0;
      const bool full = predicted == 0.0 || double(rays.size()) / predicted <= config.accel_seconds;
      std::size_t sample = rays.size();
      if (!full) {
        sample = std::min(rays.size(), std::max(kMinBruteRays, std::size_t(predicted * config.accel_seconds)));
        const double expected = double(sample) / predicted;
        if (expected > config.accel_brute_limit) {
          sample = 0;
          brute.note = "skipped: " + std::to_string(kMinBruteRays) + " rays would take about " + fixed(expected, 1) +
                       " s (limit " + fixed(config.accel_brute_limit, 1) + " s)";
        } else {
          for (std::size_t k = 0; k < sample; k++) brute.subset.push_back(k * rays.size() / sample);
          brute.note = std::to_string(sample) + " of the " + std::to_string(rays.size()) +
                       " rays, evenly spaced, one pass";
        }
      }
      if (sample > 0) {
        if (!soa) soa.emplace(scene.triangles);
        brute.pass = cpu_pass(brute, rays, [&] { bind_cpu_scene(scene, nullptr, &soa->data, soa->stride), set_cpu_accel(false); },
                              trace);
        if (full) racers.push_back(&brute);
      }
      race(racers, config.accel_seconds);
      if (sample > 0 && !full) brute.pass(true);
      for (Result* r : {&bvh_cpu, &emb, &bvh_gpu, &brute}) r->measured = r->passes > 0;
      if (bvh_gpu.measured) bvh_gpu.t = gpu->distances();
      if (brute.measured) brute_tests_per_s[set] = double(brute.rays) / brute.wall * double(n);
      bind_cpu_scene(scene, &bvh, nullptr, 0, &wide);
      for (Result* r : {&brute, &bvh_cpu, &bvh_gpu, &emb}) csv.row(set_name, level, n, *r, bvh_cpu);
    }
    if (level == levels.back()) {
      embree.reset();
      soa.reset();
      bvh = Bvh{};
      compare_builds(scene, config);  // accel_build.cpp
    }
  }
  std::ofstream run = open_csv(config, "accel_run.txt");
  run << "date: " << date << "\ncommand: " << config.command << "\nload_before: " << load_before
      << "\nload_after: " << load_average() << "\nseconds: " << fixed(seconds_since(start), 0)
      << "\nmachine: " << cpu_model()
      << "\nthreads: " << cores() << "\nseconds_per_method: " << config.accel_seconds << "\ncamera_rays: " << camera.size() << " (" << config.accel_size << "x"
      << config.accel_size << ", one random point in each pixel)\ngpu: " << (gpu ? gpu->device() : "none")
      << "\nembree: " << (EmbreeScene::available() ? EmbreeScene::version() : EmbreeScene::missing_reason()) << "\n";
  std::printf("accel: wrote %s/accel.csv, accel_build.csv and accel_run.txt\n", config.out_dir.c_str());
}

}  // namespace pt::bench
