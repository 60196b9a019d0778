// The render loop and the CPU backend (see render.h and backend.h).
#include "common/render/render.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <thread>
#include <vector>

#include "cpu/cpu_variants.h"
#include "common/base/error.h"
#include "common/render/interrupt.h"
#include "common/scene/scene.h"
#include "cpu/triangle_soa.h"

namespace pt {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The CPU backend: the stage's kernel compiled as C++, rows handed out to all cores.
class CpuBackend : public Backend {
 public:
  CpuBackend(const StageKernels& kernels, unsigned threads)
      : kernels_(kernels), threads_(threads ? threads : std::max(1u, std::thread::hardware_concurrency())) {}

  std::string kind() const override { return "cpu"; }
  std::string device_name() const override { return std::to_string(threads_) + " threads"; }

  void set_scene(const Scene& scene, uint features) override {
    kernel_ = kernels_.cpu_for(features);
    soa_ = std::make_unique<TriangleSoa>(scene.triangles);
    scene_ = KernelScene{scene.triangles.data(), scene.spheres.data(), scene.materials.data(),
                         scene.point_lights.data(), nullptr, scene.lights.data(),
                         soa_->data.data(), soa_->stride};
  }

  PassResult run_pass(const FrameParams& params, std::span<glm::vec4> out) override {
    Clock::time_point start = Clock::now();
    PassResult result;
    result.counters[kCounterNonFinitePixel] = kNoPixel;
    KernelScene scene = scene_;
    scene.counters = result.counters;
    kernel_.bind(scene, params);
    // Rows are taken a few at a time from a shared counter: cheap load balancing.
    const uint height = params.height, rows_per_task = 4;
    std::atomic<uint> next_row{0};
    auto work = [&] {
      for (uint y0; (y0 = next_row.fetch_add(rows_per_task)) < height;) {
        kernel_.render_rows(y0, std::min(height, y0 + rows_per_task), out.data());
      }
    };
    std::vector<std::thread> pool;
    for (unsigned i = 1; i < threads_; i++) pool.emplace_back(work);
    work();
    for (std::thread& t : pool) t.join();
    result.kernel_seconds = seconds_since(start);
    return result;
  }

 private:
  StageKernels kernels_;
  CpuKernel kernel_{};
  unsigned threads_;
  KernelScene scene_{};
  std::unique_ptr<TriangleSoa> soa_;  // the triangles as arrays for the block test
};

void print_progress(const RenderSettings& s, std::uint64_t done, double elapsed) {
  if (s.time_budget > 0.0 || s.target_error > 0.0) {  // no fixed end: say where it stands
    std::fprintf(stderr, "\r%s: %llu spp, %.1f s elapsed%s   ", s.label, (unsigned long long)done, elapsed,
                 s.time_budget > 0.0 ? (" of " + std::to_string(int(s.time_budget)) + " s").c_str() : "");
    std::fflush(stderr);
    return;
  }
  double left = elapsed / double(done) * double(s.spp - done);
  std::fprintf(stderr, "\r%s: %3d%% (%llu/%llu spp), %.1f s elapsed, about %.1f s left   ", s.label,
               int(100.0 * double(done) / double(s.spp)), (unsigned long long)done, (unsigned long long)s.spp,
               elapsed, left);
  std::fflush(stderr);
}

}  // namespace

const CpuKernel& StageKernels::cpu_for(uint features) const {
  return cpu[cpu_variant_index(features, unsigned(cpu.size()))];
}

std::unique_ptr<Backend> make_cpu_backend(const StageKernels& kernels, unsigned threads) {
  return std::make_unique<CpuBackend>(kernels, threads);
}

std::uint64_t pass_samples(std::uint64_t index) {
  // 1, 2, 4, 8, 16, 16, ...
  return index >= 4 ? kMaxPassSamples : std::min(kMaxPassSamples, std::uint64_t(1) << index);
}

std::uint64_t available_memory_bytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  std::uint64_t kb;
  std::string unit;
  while (meminfo >> key >> kb >> unit) {
    if (key == "MemAvailable:") return kb * 1024;
  }
  return std::uint64_t(sysconf(_SC_PHYS_PAGES)) * std::uint64_t(sysconf(_SC_PAGE_SIZE));
}

void check_image_memory(int width, int height, bool resuming) {
  // Film: 4 doubles per pixel (twice while a checkpoint's film is read in); pass buffer: 4
  // floats per pixel; output: 3 floats.
  const std::uint64_t films = resuming ? 2 : 1;
  const std::uint64_t host_per_pixel = films * 4 * sizeof(double) + 4 * sizeof(float) + 3 * sizeof(float);
  std::uint64_t pixels = std::uint64_t(width) * std::uint64_t(height), bytes = 0;
  if (pixels > (std::uint64_t(1) << 31)) {
    throw Error(kExitBadOption, "image " + std::to_string(width) + "x" + std::to_string(height) +
                                    " has more than 2^31 pixels; render a smaller image");
  }
  if (__builtin_mul_overflow(pixels, host_per_pixel, &bytes) || bytes > available_memory_bytes()) {
    char line[256];
    std::snprintf(line, sizeof line, "image %dx%d needs %.1f GB of memory, this machine has %.1f GB available; "
                  "render a smaller image", width, height, double(pixels) * double(host_per_pixel) / 1e9,
                  double(available_memory_bytes()) / 1e9);
    throw Error(kExitBadOption, line);
  }
}

void RenderCounters::add(const PassResult& pass) {
  depth_cap += pass.counters[kCounterDepthCap];
  zero_pdf += pass.counters[kCounterZeroPdf];
  non_finite += pass.counters[kCounterNonFinite];
  loop_limit += pass.counters[kCounterLoopLimit];
  first_non_finite_pixel = std::min(first_non_finite_pixel, pass.counters[kCounterNonFinitePixel]);
}

FrameParams make_frame_params(const Scene& scene, const RenderSettings& s) {
  FrameParams p{};
  p.camera = make_camera(scene, float(s.width) / float(s.height));
  p.sky = s.sky;
  p.width = uint(s.width), p.height = uint(s.height);
  p.triangle_count = uint(scene.triangles.size());
  p.sphere_count = uint(scene.spheres.size());
  p.material_count = uint(scene.materials.size());
  p.point_light_count = uint(scene.point_lights.size());
  p.seed = s.seed, p.roulette = s.roulette, p.depth_cap = s.depth_cap;
  p.light_count = uint(scene.lights.size());
  p.sky_pick = sky_pick_probability(scene, s.sky);
  Bounds b = scene.bounds();
  p.scene_radius = b.empty() ? 1.0f : glm::max(0.5f * glm::length(b.hi - b.lo), 1e-30f);
  return p;
}

RenderResult render(Backend& backend, const Scene& scene, const RenderSettings& s) {
  RenderResult result = s.resume ? *s.resume : RenderResult{Film(s.width, s.height), 0.0, 0.0, {}, 0, {}};
  result.device_error.clear();
  const double seconds_before = result.seconds;
  FrameParams params = make_frame_params(scene, s);
  std::vector<glm::vec4> pass(std::size_t(s.width) * std::size_t(s.height));
  bool show_progress = s.progress && ::isatty(2);
  bool shown = false;
  Clock::time_point start = Clock::now(), saved = start;
  std::uint64_t done = result.film.spp();
  try {
    backend.set_scene(scene, s.all_features ? kFeatureAll : scene_feature_mask(scene, s.sky));
  } catch (const Error& e) {  // a device that cannot hold the scene: nothing rendered yet
    if (e.code() != kExitNoDevice) throw;
    result.device_error = e.what();
    return result;
  }
  for (std::uint64_t index = result.passes; done < s.spp; index++) {
    std::uint64_t n = std::min(pass_samples(index), s.spp - done);
    params.first_sample = uint(done);
    params.sample_count = uint(n);
    PassResult pass_result;
    try {
      pass_result = backend.run_pass(params, pass);
    } catch (const Error& e) {  // a lost device: keep the samples done so far
      if (e.code() != kExitNoDevice) throw;
      result.device_error = e.what();
      if (s.save && done > 0) s.save(result);
      break;
    }
    result.kernel_seconds += pass_result.kernel_seconds;
    result.counters.add(pass_result);
    result.film.add_pass(pass, n);
    done += n;
    result.passes = index + 1;
    double elapsed = seconds_since(start);
    result.seconds = seconds_before + elapsed;
    if (show_progress && elapsed > 1.0 && done < s.spp) print_progress(s, done, elapsed), shown = true;
    // Ctrl-C or SIGTERM: stop here; the samples done so far make a correct image. Or the
    // user's trade of time for accuracy: every pass ends a correct image of its spp.
    bool stop = interrupt_signal() != 0 || (s.time_budget > 0.0 && elapsed >= s.time_budget) ||
                (s.target_error > 0.0 && done >= kMinSamplesForError &&
                 result.film.relative_standard_error() <= s.target_error);
    if (s.save && done < s.spp && (stop || seconds_since(saved) >= s.save_seconds)) {
      s.save(result);
      saved = Clock::now();
    }
    if (stop) break;
  }
  if (shown) std::fprintf(stderr, "\r%*s\r", 79, "");
  result.seconds = seconds_before + seconds_since(start);
  return result;
}

}  // namespace pt
