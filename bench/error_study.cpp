// pt_bench: error against time (issue 6). Each run renders its scene at 1, 2, 4, ... samples
// per pixel through the renderer's own loop (common/render/render.h), each checkpoint a fresh
// render of that many samples, so its time is what a user waits for that image. At each:
// wall and kernel time, samples per second, RMSE and relative RMSE against the true image,
// Monte Carlo efficiency 1 / (MSE x time), and the error the renderer itself estimates.
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "bench/bench.h"
#include "common/base/error.h"

namespace pt::bench {

namespace {

// The last checkpoint is the first to reach this many seconds or this many samples.
constexpr std::uint64_t kMaxSpp = std::uint64_t(1) << 20;

}  // namespace

void run_error_study(const std::vector<Run>& runs, const Config& config) {
  std::ofstream csv = open_csv(config, "convergence.csv");
  csv << "scene,stage,backend,device,width,height,spp,wall_s,kernel_s,samples_per_s,rmse,rel_rmse,efficiency,"
         "est_rel_error,reference,reference_rel_error,roulette\n";
  std::map<std::string, Reference> references;
  for (const Run& run : runs) {
    if (!references.count(run.scene)) references[run.scene] = reference_image(run.scene, config);
    const Reference& ref = references[run.scene];
    Scene scene = load_bench_scene(run.scene);
    Backend& backend = backend_for(run.stage, run.backend);
    // The BVH once per scene; each render's time counts its build, as a run of the program would.
    const Bvh bvh = build_bvh(scene.triangles);
    RenderHooks hooks;
    hooks.bvh = &bvh;
    std::printf("%-18s %-22s %-3s", run.scene.c_str(), stage_name(run.stage).c_str(), run.backend.c_str());
    std::fflush(stdout);
    for (std::uint64_t spp = 1; spp <= kMaxSpp; spp *= 2) {
      RenderSettings s;
      s.width = s.height = config.size;
      s.spp = spp;
      s.seed = config.seed;
      s.roulette = config.roulette;  // one roulette for every stage (--rr)
      RenderResult r = render(backend, scene, s, hooks);
      if (r.bvh) r.seconds += bvh.stats.build_seconds;
      ErrorMetrics e = compare_images(r.film.mean_rgb(), ref, config.size);
      double samples = double(config.size) * config.size * double(spp);
      double mse = e.rmse * e.rmse;
      char line[512];
      std::snprintf(line, sizeof line, "%s,%s,%s,\"%s\",%d,%d,%llu,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,\"%s\",%.4g,%s\n",
                    run.scene.c_str(), stage_name(run.stage).c_str(), run.backend.c_str(),
                    backend.device_name().c_str(), config.size, config.size, (unsigned long long)spp, r.seconds,
                    r.kernel_seconds, samples / r.seconds, e.rmse, e.relative,
                    mse > 0.0 ? 1.0 / (mse * r.seconds) : 0.0, r.film.relative_standard_error(), ref.source.c_str(),
                    ref.relative_error, config.roulette == kRouletteFixed ? "fixed" : "throughput");
      csv << line << std::flush;
      if (r.seconds >= config.seconds) {
        std::printf(" %8llu spp %7.2f s  rel RMSE %.4f\n", (unsigned long long)spp, r.seconds, e.relative);
        break;
      }
    }
  }
}

}  // namespace pt::bench
