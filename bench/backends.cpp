// pt_bench: the stages' kernels and backends by name, and the scenes (bench.h).
#include <algorithm>
#include <ctime>
#include <filesystem>
#include <map>
#include <thread>

#include "bench/bench.h"
#include "cpu/cpu_backend.h"
#include "common/base/error.h"
#include "common/scene/scene_loading.h"
#include "gpu/gpu_backend.h"
#include "stage1_raycast/kernels.h"
#include "stage2_montecarlo/kernels.h"
#include "stage3_importance/kernels.h"
#include "stage4_direct_indirect/kernels.h"
#include "stage5_mis/kernels.h"
#include "stage6_variance_aware/kernels.h"

namespace pt::bench {

std::string stage_name(const std::string& stage) {
  static const char* names[] = {"stage1_raycast", "stage2_montecarlo", "stage3_importance", "stage4_direct_indirect",
                                "stage5_mis", "stage6_variance_aware"};
  for (int i = 0; i < 6; i++) {
    if (stage == names[i] || stage == std::to_string(i + 1) || stage == std::string(names[i]).substr(0, 6)) return names[i];
  }
  throw Error(kExitBadOption, "unknown stage '" + stage + "'; use 1..6 or a program name such as stage2_montecarlo");
}

StageKernels stage_kernels(const std::string& stage) {
  std::string name = stage_name(stage);
  if (name == "stage1_raycast") return stage1::kernels();
  if (name == "stage2_montecarlo") return stage2::kernels();
  if (name == "stage3_importance") return stage3::kernels();
  if (name == "stage4_direct_indirect") return stage4::kernels();
  if (name == "stage5_mis") return stage5::kernels();
  return stage6::kernels();
}

Backend& backend_for(const std::string& stage, const std::string& kind) {
  static std::map<std::string, std::unique_ptr<Backend>> backends;
  std::string key = stage_name(stage) + "/" + kind;
  std::unique_ptr<Backend>& b = backends[key];
  if (!b) {
    if (kind == "cpu") {
      b = make_cpu_backend(stage_kernels(stage));
    } else if (kind == "gpu") {
      b = gpu::create_backend(stage_kernels(stage), "");
    } else {
      throw Error(kExitBadOption, "unknown backend '" + kind + "'; use cpu or gpu");
    }
  }
  return *b;
}

Scene load_bench_scene(const std::string& scene) {
  bool path = scene.find('/') != std::string::npos || scene.find(".gl") != std::string::npos;
  return load_scene(path || scene.rfind("builtin:", 0) == 0 ? scene : "builtin:" + scene);
}

Rate samples_per_second(Backend& backend, const Scene& scene, const RenderSettings& s) {
  double cpu0 = double(std::clock()) / CLOCKS_PER_SEC;
  RenderResult r = render(backend, scene, s);
  double cpu = double(std::clock()) / CLOCKS_PER_SEC - cpu0;
  double samples = double(s.width) * s.height * double(s.spp);
  return Rate{samples / r.seconds, samples / cpu * std::max(1u, std::thread::hardware_concurrency())};
}

std::ofstream open_csv(const Config& config, const std::string& name) {
  std::filesystem::create_directories(config.out_dir);
  std::string path = config.out_dir + "/" + name;
  std::ofstream csv(path);
  if (!csv) throw Error(kExitOutput, "cannot write " + path + "; check --out");
  return csv;
}

}  // namespace pt::bench
