// The CPU backend (the "cpu/": tiles on all cores, SIMD lanes, runtime dispatch):
// a stage's kernel compiled as C++ (cmake/PtStage.cmake) run over rows of the image on all
// cores, in the copy specialised to the scene's features (cpu_variants.h).
#include "cpu/cpu_backend.h"

#include <algorithm>
#include <atomic>
#include <cerrno>  // program_invocation_short_name (GNU)
#include <chrono>
#include <cstdio>
#include <cstring>
#include <span>
#include <system_error>
#include <thread>
#include <vector>

#include "common/render/render.h"
#include "common/scene/bvh.h"
#include "common/scene/environment.h"
#include "common/scene/scene.h"
#include "cpu/cpu_variants.h"
#include "cpu/sphere_soa.h"
#include "cpu/triangle_soa.h"
#include "cpu/wide_bvh.h"

namespace pt {

namespace {

using Clock = std::chrono::steady_clock;

// cpu_stages_run(): a bit per stage number, set by every pass.
std::atomic<std::uint32_t> stages_run{0};

// The bit of a stage's kernel in stages_run ("stage4_direct_indirect": bit 3), 0 for a kernel
// that is not a stage's (the tests' own).
std::uint32_t stage_bit(const char* name) {
  if (std::strncmp(name, "stage", 5) != 0 || name[5] < '1' || name[5] > '9') return 0;
  return 1u << (name[5] - '1');
}

// The copy of the kernel built for (at least) the scene features `features` (kFeature* bits).
const CpuKernel& cpu_kernel_for(const StageKernels& kernels, uint features) {
  return kernels.cpu[cpu_variant_index(features, unsigned(kernels.cpu.size()))];
}

// The CPU backend: the stage's kernel compiled as C++, rows handed out to all cores.
class CpuBackend : public Backend {
 public:
  CpuBackend(const StageKernels& kernels, unsigned threads)
      : kernels_(kernels), threads_(threads ? threads : std::max(1u, std::thread::hardware_concurrency())) {}

  std::string kind() const override { return "cpu"; }
  std::string device_name() const override { return std::to_string(threads_) + " threads"; }
  BeforeRender before_render() const override { return kernels_.before_render; }

  void set_scene(const Scene& scene, uint features, const Bvh* bvh) override {
    kernel_ = cpu_kernel_for(kernels_, features);
    // The triangles as arrays are made by the first pass that searches them by brute force
    // (run_pass): with a BVH no pass reads them, and on 1.3 M triangles they cost as much
    // CPU time as 0.2 M camera rays (issue 50, docs/acceleration.md).
    triangles_ = scene.triangles;
    soa_.reset();
    scene_ = KernelScene{scene.triangles.data(), scene.spheres.data(), scene.materials.data(),
                         scene.point_lights.data(), nullptr, scene.lights.data()};
    scene_.light_alias = scene.light_alias.data();
    scene_.light_runs = scene.light_runs.data();
    scene_.light_run_count = uint(scene.light_runs.size());
    scene_.triangle_light_count = scene.triangle_light_count;
    scene_.features = features;  // read by a copy built for the features at run time (kernel_bindings.h)
    sphere_soa_ = std::make_unique<SphereSoa>(scene.spheres);
    scene_.sphere_soa = sphere_soa_->data.data();
    scene_.sphere_soa_stride = sphere_soa_->stride;
    scene_.sphere_soa_count = sphere_soa_->count;
    // Textures and vertex colours; without them, neutral material entries for a copy of
    // the kernel that has texture code (texture.glsl reads nothing more then).
    if (uses_textures(scene)) {
      scene_.triangle_attributes = scene.triangle_attributes.data();
      scene_.material_textures = scene.material_textures.data();
      scene_.textures = scene.textures.data();
      scene_.texels = scene.texels.data();
    } else {
      neutral_ = neutral_material_textures(scene.materials.size());
      scene_.material_textures = neutral_.data();
    }
    if (uses_shading_normals(scene)) scene_.triangle_shading = scene.triangle_shading.data();
    if (scene.environment) {
      scene_.environment_radiance = scene.environment->radiance.data();
      scene_.environment_tables = scene.environment->table.data();
    }
    wide_.reset();
    if (bvh && !bvh->nodes.empty()) {
      scene_.bvh_nodes = bvh->nodes.data(), scene_.bvh_indices = bvh->indices.data();
      // The CPU walks the tree collapsed to 8 children and leaf blocks (wide_bvh.h): the
      // one handed for this tree (give_cpu_wide_bvh), else made here.
      if (bvh != given_for_ || !given_wide_) wide_ = std::make_unique<WideBvh>(build_wide_bvh(*bvh, scene.triangles));
      scene_.wide_bvh = wide_ ? wide_.get() : given_wide_;
    }
  }

  void give_wide_bvh(const Bvh* bvh, const WideBvh* wide) { given_for_ = bvh, given_wide_ = wide; }

  PassResult run_pass(const FrameParams& params, std::span<glm::vec4> out) override {
    Clock::time_point start = Clock::now();
    PassResult result;  // its counters start at zero, kNoPixel for the pixel index
    // nearest_triangle() (cpu/triangle_lanes.h) reads the arrays only without a BVH.
    if ((params.accel != kAccelBvh || scene_.bvh_nodes == nullptr) && !soa_ && !triangles_.empty()) {
      soa_ = std::make_unique<TriangleSoa>(triangles_);
      scene_.triangle_soa = soa_->data.data(), scene_.triangle_soa_stride = soa_->stride;
    }
    stages_run.fetch_or(stage_bit(kernels_.name), std::memory_order_relaxed);
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
    // No more threads than there are tasks. A thread the system refuses (a process or
    // memory limit) is not an error: the threads already started, and this one, do the
    // work, and later passes ask for no more than that (said once on stderr).
    const unsigned tasks = (height + rows_per_task - 1) / rows_per_task;
    const unsigned wanted = std::max(1u, std::min(threads_, tasks));
    std::vector<std::thread> pool;
    try {
      while (pool.size() + 1 < wanted) pool.emplace_back(work);
    } catch (const std::system_error& e) {
      std::fprintf(stderr, "%s: the system started only %zu of the %u CPU threads asked for (%s); rendering with %zu\n",
                   program_invocation_short_name, pool.size() + 1, threads_, e.what(), pool.size() + 1);
      threads_ = unsigned(pool.size() + 1);
    }
    work();
    for (std::thread& t : pool) t.join();
    result.kernel_seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return result;
  }

 private:
  StageKernels kernels_;
  CpuKernel kernel_{};
  unsigned threads_;
  KernelScene scene_{};
  std::span<const Triangle> triangles_;  // the scene's, for the arrays below
  std::unique_ptr<TriangleSoa> soa_;  // the triangles as arrays for the block test, once needed
  std::unique_ptr<SphereSoa> sphere_soa_;  // the spheres as arrays for theirs
  std::unique_ptr<WideBvh> wide_;     // the BVH collapsed for the SIMD walk, or none
  const Bvh* given_for_ = nullptr;    // give_cpu_wide_bvh(): a tree and its wide form
  const WideBvh* given_wide_ = nullptr;
  std::vector<MaterialTextures> neutral_;  // material_textures[] of a scene without textures
};

}  // namespace

std::unique_ptr<Backend> make_cpu_backend(const StageKernels& kernels, unsigned threads) {
  return std::make_unique<CpuBackend>(kernels, threads);
}

std::uint32_t cpu_stages_run() { return stages_run.load(std::memory_order_relaxed); }
void clear_cpu_stages_run() { stages_run.store(0, std::memory_order_relaxed); }

void give_cpu_wide_bvh(Backend& backend, const Bvh* bvh, const WideBvh* wide) {
  if (auto* cpu = dynamic_cast<CpuBackend*>(&backend)) cpu->give_wide_bvh(bvh, wide);
}

}  // namespace pt
