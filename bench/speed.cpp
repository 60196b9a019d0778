// pt_bench's speed section (issue 6, "Speed targets"): rays per second of brute-force
// closest-hit ray casting on the Cornell box. Three measurements in the same run: the
// renderer's own intersect_scene() (common/kernel/intersect.glsl compiled as C++, as the
// CPU kernels compile it), the structure-of-arrays reference loop (soa_reference.cpp), and
// stage1_raycast (one camera ray per sample, Eq. 2) on each backend, whose samples per
// second are rays per second with the camera and the film's work on top. On the GPU also
// the naive GLSL loop (the device's reference) and intersect_scene() alone (speed_gpu.cpp).
#include <atomic>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>

#include "bench/bench.h"
#include "bench/soa_reference.h"
#include "bench/speed_gpu.h"
#include "common/base/error.h"
#include "cpu/kernel_prelude.h"
#include "cpu/triangle_soa.h"

namespace {
namespace kernel {  // the renderer's intersection code, as a CPU kernel compiles it
#include "cpu/kernel_begin.h"
#include "common/kernel/camera.glsl"
#include "common/kernel/intersect.glsl"
#include "cpu/kernel_support.h"
}  // namespace kernel
}  // namespace

namespace pt::bench {

namespace {

using Clock = std::chrono::steady_clock;

// Runs work(first, count) over `count` rays split across the cores, again and again until
// a second has passed.
template <class F> Rate rays_per_second(std::size_t count, F work) {
  unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  std::uint64_t done = 0;
  std::atomic<double> cpu_seconds{0.0};
  Clock::time_point start = Clock::now();
  double seconds = 0.0;
  while (seconds < 1.0) {
    std::vector<std::thread> pool;
    for (unsigned i = 0; i < threads; i++) {
      std::size_t a = count * i / threads, b = count * (i + 1) / threads;
      pool.emplace_back([&, a, b] {
        double t0 = thread_cpu_seconds();
        work(a, b - a);
        cpu_seconds.fetch_add(thread_cpu_seconds() - t0);
      });
    }
    for (std::thread& t : pool) t.join();
    done += count;
    seconds = std::chrono::duration<double>(Clock::now() - start).count();
  }
  return Rate{double(done) / seconds, double(done) / cpu_seconds.load() * threads};
}

// stage1 by the wall clock; "cpu" rate: by the process's CPU time (all its threads; on the
// GPU backend that is lavapipe's threads too), times the cores.
Rate stage1_samples_per_second(const std::string& backend, const Scene& scene) {
  RenderSettings s;
  s.width = s.height = 256;
  s.spp = 64;
  Backend& b = backend_for("1", backend);
  render(b, scene, s);  // warm up: the GPU compiles its pipeline
  return samples_per_second(b, scene, s);
}

}  // namespace

void run_speed(const Config& config) {
  Scene scene = load_bench_scene("cornell");
  // Camera rays through random points of a square image, the same for every method.
  const std::size_t count = 1 << 18;
  Camera cam = make_camera(scene, 1.0f);
  std::vector<glm::vec3> origins(count), dirs(count);
  std::mt19937 rng(config.seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (std::size_t i = 0; i < count; i++) {
    kernel::Ray r = kernel::camera_ray(cam, glm::vec2(u(rng), u(rng)));
    origins[i] = r.origin, dirs[i] = r.dir;
  }
  kernel::triangles = scene.triangles.data();
  kernel::spheres = scene.spheres.data();
  kernel::params.triangle_count = uint(scene.triangles.size());
  kernel::params.sphere_count = uint(scene.spheres.size());
  pt::TriangleSoa triangle_soa(scene.triangles);  // as the CPU backend binds it (render.cpp)
  kernel::triangle_soa = triangle_soa.data.data();
  kernel::triangle_soa_stride = triangle_soa.stride;
  std::atomic<double> sink{0.0};  // the sums keep the work alive
  Rate renderer = rays_per_second(count, [&](std::size_t first, std::size_t n) {
    double sum = 0.0;
    for (std::size_t i = first; i < first + n; i++) {
      sum += kernel::intersect_scene(kernel::Ray(origins[i], dirs[i]), kernel::kInfinity).t;
    }
    sink.fetch_add(sum);
  });
  SoaTriangles soa;
  for (const Triangle& t : scene.triangles) soa.add(t.p0, t.p1, t.p2);
  Rate reference = rays_per_second(count, [&](std::size_t first, std::size_t n) {
    sink.fetch_add(soa_closest_hits(soa, origins.data() + first, dirs.data() + first, n));
  });
  Rate reference_avx2 = rays_per_second(count, [&](std::size_t first, std::size_t n) {
    sink.fetch_add(soa_closest_hits(soa, origins.data() + first, dirs.data() + first, n, true));
  });

  std::ofstream csv = open_csv(config, "speed.csv");
  csv << "method,backend,device,mrays_per_s,mrays_per_cpu_s,target_mrays_per_s\n";
  unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  auto row = [&](const char* method, const std::string& backend, const std::string& device, Rate rays, double target) {
    csv << "\"" << method << "\"," << backend << ",\"" << device << "\"," << rays.wall / 1e6 << "," << rays.cpu / 1e6 << ","
        << target << "\n";
    std::printf("%-30s %-4s %-34s %6.2f M rays/s (by CPU time %6.2f)%s\n", method, backend.c_str(), device.c_str(),
                rays.wall / 1e6, rays.cpu / 1e6,
                target > 0.0 ? (", target " + std::to_string(int(target))).c_str() : "");
  };
  std::string cpu = std::to_string(threads) + " threads";
  row("intersect_scene (renderer)", "cpu", cpu, renderer, 20.0);
  row("SoA reference loop (-O3)", "cpu", cpu, reference, 0.0);
  row("SoA reference loop (-O3, AVX2)", "cpu", cpu, reference_avx2, 0.0);
  row("stage1_raycast samples/s", "cpu", backend_for("1", "cpu").device_name(), stage1_samples_per_second("cpu", scene), 20.0);
  try {
    GpuRayRates g = gpu_rays_per_second(scene, origins, dirs);
    row("naive GLSL loop (reference)", "gpu", g.device, g.naive, 0.0);
    row("intersect_scene (renderer)", "gpu", g.device, g.renderer, 10.0);
    if (g.hit_mismatch > 1e-3) std::printf("gpu: the two kernels disagree on %.2f%% of the rays\n", 100.0 * g.hit_mismatch);
    Backend& gpu = backend_for("1", "gpu");
    row("stage1_raycast samples/s", "gpu", gpu.device_name(), stage1_samples_per_second("gpu", scene), 10.0);
  } catch (const Error& e) {
    std::printf("gpu: %s (no GPU row)\n", e.what());
  }
  if (sink.load() == 1.2345) std::printf(" ");
}

}  // namespace pt::bench
