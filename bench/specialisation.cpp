// pt_bench's specialisation section (issue 8, "Specialised kernels"): samples per second
// of each stage's kernel specialised to the scene's features (the default) against the
// general kernel (--all-features), on the Cornell box (triangles, diffuse, area light) and
// on builtin:every_feature under a sky (every feature the renderer models).
#include <algorithm>
#include <cstdio>
#include <ctime>
#include <thread>
#include <filesystem>
#include <fstream>

#include "bench/bench.h"
#include "common/base/error.h"

namespace pt::bench {

void run_specialisation(const std::vector<std::string>& stages, const std::vector<std::string>& backends,
                        const Config& config) {
  std::ofstream csv = open_csv(config, "specialisation.csv");
  csv << "scene,stage,backend,spp,specialised_samples_per_s,general_samples_per_s,ratio,"
         "specialised_per_cpu_s,general_per_cpu_s,cpu_ratio\n";
  struct Case {
    const char* scene;
    glm::vec3 sky;
  };
  const Case cases[] = {{"cornell", glm::vec3(0.0f)}, {"every_feature", glm::vec3(0.1f)}};
  for (const Case& c : cases) {
    Scene scene = load_bench_scene(c.scene);
    for (const std::string& stage : stages) {
      for (const std::string& kind : backends) {
        Backend& backend = backend_for(stage, kind);
        RenderSettings s;
        s.width = s.height = config.size;
        s.sky = c.sky;
        s.seed = config.seed;
        // Warm both pipelines up and size the runs to about a second each.
        s.spp = 4;
        double rate = samples_per_second(backend, scene, s).wall;
        s.all_features = true;
        samples_per_second(backend, scene, s);
        s.spp = std::clamp<std::uint64_t>(std::uint64_t(rate / (double(s.width) * s.height)), 4, 1 << 16);
        Rate best[2];  // specialised, general: the best of three alternating runs
        for (int round = 0; round < 3; round++) {
          for (int general = 0; general < 2; general++) {
            s.all_features = general == 1;
            Rate r = samples_per_second(backend, scene, s);
            best[general].wall = std::max(best[general].wall, r.wall);
            best[general].cpu = std::max(best[general].cpu, r.cpu);
          }
        }
        char line[256];
        std::snprintf(line, sizeof line, "%s,%s,%s,%llu,%.4g,%.4g,%.3f,%.4g,%.4g,%.3f\n", c.scene,
                      stage_name(stage).c_str(), kind.c_str(), (unsigned long long)s.spp, best[0].wall, best[1].wall,
                      best[0].wall / best[1].wall, best[0].cpu, best[1].cpu, best[0].cpu / best[1].cpu);
        csv << line << std::flush;
        std::printf("%-14s %-22s %-3s specialised %9.3g, general %9.3g samples/s: x%.2f (by CPU time x%.2f)\n",
                    c.scene, stage_name(stage).c_str(), kind.c_str(), best[0].wall, best[1].wall,
                    best[0].wall / best[1].wall, best[0].cpu / best[1].cpu);
      }
    }
  }
}

}  // namespace pt::bench
