// pt_bench: the speed-versus-accuracy lab (issue 6) and the measured gain of specialised
// kernels (issue 8). Sections: `error` (error against time per scene x stage x backend,
// docs/results/convergence.csv), `speed` (rays per second, speed.csv), `special`
// (specialised against general kernels, specialisation.csv), `accel` (issue 17: rays per
// second against the triangle count, brute force, BVH and Embree, accel.csv), `stage` (issue
// 50: stage programs on the 1.3 M-triangle mesh beside Embree on their rays, accel_stage.csv,
// not in the default list). bench/run.sh
// runs them all and makes the plots and docs/results.md.
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>

#include <CLI/CLI.hpp>

#include "bench/bench.h"
#include "common/app/app.h"
#include "common/base/error.h"

namespace {

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, sep);) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

// The run list: one line per scene, "SCENE STAGES BACKENDS" (e.g. "cornell 2,3,4 cpu,gpu"),
// '#' starts a comment. Lines are kept when they pass the command line's filters.
std::vector<pt::bench::Run> read_runs(const std::string& path, const std::set<std::string>& scenes,
                                      const std::set<std::string>& stages, const std::set<std::string>& backends) {
  std::ifstream in(path);
  if (!in) throw pt::Error(pt::kExitBadOption, "cannot read the run list " + path + "; give one with --runs");
  std::vector<pt::bench::Run> runs;
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    number++;
    line = line.substr(0, line.find('#'));
    std::stringstream fields(line);
    std::string scene, stage_list, backend_list, extra;
    if (!(fields >> scene)) continue;
    if (!(fields >> stage_list >> backend_list) || (fields >> extra)) {
      throw pt::Error(pt::kExitBadOption, path + ":" + std::to_string(number) +
                                              ": expected 'SCENE STAGES BACKENDS', e.g. 'cornell 2,3,4 cpu,gpu'");
    }
    if (!scenes.empty() && !scenes.count(scene)) continue;
    for (const std::string& stage : split(stage_list, ',')) {
      std::string name = pt::bench::stage_name(stage);
      if (!stages.empty() && !stages.count(name)) continue;
      for (const std::string& backend : split(backend_list, ',')) {
        if (backend != "cpu" && backend != "gpu") {
          throw pt::Error(pt::kExitBadOption, path + ":" + std::to_string(number) + ": unknown backend '" + backend +
                                                  "'; use cpu or gpu");
        }
        if (!backends.empty() && !backends.count(backend)) continue;
        runs.push_back({scene, name, backend});
      }
    }
  }
  return runs;
}

}  // namespace

int main(int argc, char** argv) {
  return pt::run_guarded("pt_bench", [&] {
    pt::bench::Config config;
    std::string runs_path = "bench/runs.txt";
    std::vector<std::string> scenes, stages, backends, sections{"error", "speed", "special", "accel"};
    CLI::App app{"pt_bench: error against time per scene, stage and backend; rays per second; specialised "
                 "against general kernels. CSV files into --out."};
    app.add_option("--runs", runs_path, "the run list: lines 'SCENE STAGES BACKENDS'")->capture_default_str();
    app.add_option("--scene", scenes, "only these scenes of the run list (repeatable)");
    app.add_option("--stage", stages, "only these stages: 1..6 or program names (repeatable)");
    app.add_option("--backend", backends, "only these backends: cpu, gpu (repeatable)");
    app.add_option("--section", sections, "error, speed, special, accel, stage (repeatable)")->capture_default_str();
    app.add_option("--size", config.size, "image width and height")->capture_default_str()->check(CLI::Range(1, 4096));
    app.add_option("--seconds", config.seconds, "per run: stop after the first checkpoint that takes this long")
        ->capture_default_str()->check(CLI::PositiveNumber);
    app.add_option("--reference-seconds", config.reference_seconds, "render time of a cached reference")
        ->capture_default_str()->check(CLI::PositiveNumber);
    app.add_option("--cache", config.cache_dir, "directory of the cached references")->capture_default_str();
    app.add_option("--out", config.out_dir, "directory of the CSV files")->capture_default_str();
    app.add_option("--seed", config.seed, "seed of the study's renders")->capture_default_str();
    std::string rr = "throughput";
    app.add_option("--rr", rr,
                   "the error study's Russian roulette, for every stage: throughput (the default of stages 3 to 5) or "
                   "fixed (the article's p = 1/2, stage2's default)")
        ->capture_default_str()->check(CLI::IsMember({"throughput", "fixed"}));
    app.add_option("--accel-size", config.accel_size, "accel: camera rays per side of the image")
        ->capture_default_str()->check(CLI::Range(1, 4096));
    app.add_option("--accel-max-level", config.accel_max_level, "accel: the largest icosphere, 20 * 4^level triangles")
        ->capture_default_str()->check(CLI::Range(1, 9));
    app.add_option("--accel-seconds", config.accel_seconds, "accel: seconds per method, scene and ray set")
        ->capture_default_str()->check(CLI::PositiveNumber);
    app.add_option("--accel-brute-limit", config.accel_brute_limit,
                   "accel: the brute force skips a triangle count it would spend longer on (seconds)")
        ->capture_default_str()->check(CLI::PositiveNumber);
    app.add_option("--stage-size", config.stage_size, "stage: stage1's image side (stage4: half of it)")
        ->capture_default_str()->check(CLI::Range(2, 4096));
    app.add_option("--stage-rounds", config.stage_rounds, "stage: alternating rounds per measurement")
        ->capture_default_str()->check(CLI::Range(1, 100));
    app.add_option("--stage-views", config.stage_views,
                   "stage: only these of stage1:inside, stage1:outside, stage1:grazing, stage4:inside, stage4:outside (repeatable)");
    try {
      app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
      app.exit(e);
      return 0;
    } catch (const CLI::ParseError& e) {
      std::fprintf(stderr, "pt_bench: %s; see --help\n", e.what());
      return int(pt::kExitBadOption);
    }
    config.roulette = rr == "fixed" ? pt::kRouletteFixed : pt::kRouletteThroughput;
    std::set<std::string> stage_set, backend_set(backends.begin(), backends.end());
    for (const std::string& s : stages) stage_set.insert(pt::bench::stage_name(s));
    for (const std::string& b : backends) {
      if (b != "cpu" && b != "gpu") throw pt::Error(pt::kExitBadOption, "unknown backend '" + b + "'; use cpu or gpu");
    }
    std::set<std::string> section_set(sections.begin(), sections.end());
    for (const std::string& s : section_set) {
      if (s != "error" && s != "speed" && s != "special" && s != "accel" && s != "stage") {
        throw pt::Error(pt::kExitBadOption, "unknown section '" + s + "'; use error, speed, special, accel or stage");
      }
    }
    if (section_set.count("error")) {
      std::vector<pt::bench::Run> runs =
          read_runs(runs_path, std::set<std::string>(scenes.begin(), scenes.end()), stage_set, backend_set);
      std::printf("== error against time: %zu runs, %dx%d, %.1f s each\n", runs.size(), config.size, config.size,
                  config.seconds);
      pt::bench::run_error_study(runs, config);
    }
    if (section_set.count("speed")) {
      std::printf("== rays per second, Cornell box\n");
      pt::bench::run_speed(config);
    }
    if (section_set.count("special")) {
      std::vector<std::string> st = stages.empty() ? std::vector<std::string>{"1", "2", "3", "4"} : stages;
      std::vector<std::string> bk = backends.empty() ? std::vector<std::string>{"cpu", "gpu"} : backends;
      std::printf("== specialised against general kernels\n");
      pt::bench::run_specialisation(st, bk, config);
    }
    if (section_set.count("accel")) {
      for (int i = 0; i < argc; i++) config.command += (i ? " " : "") + std::string(argv[i]);
      std::printf("== rays per second against the triangle count (issue 17)\n");
      pt::bench::run_accel(config);
    }
    if (section_set.count("stage")) {
      if (config.command.empty()) {
        for (int i = 0; i < argc; i++) config.command += (i ? " " : "") + std::string(argv[i]);
      }
      std::printf("== stage programs on the 1.3M-triangle mesh beside Embree on their rays (issue 50)\n");
      pt::bench::run_accel_stage(config);
    }
    return 0;
  });
}
