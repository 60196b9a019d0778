// pt_bench's stage section (issue 50; accel_stage.h): stage1 and stage4 on the 1.3 M-triangle
// furnace_mesh from three viewpoints, end to end by CPU time, beside the wide BVH's walk and
// Embree 3 on the very rays the stage traces, and a sample's cost split into its parts
// (accel_stage.csv). Not part of the article: machinery for measuring the BVH after it.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <optional>
#include <thread>

#include <glm/gtc/matrix_transform.hpp>

#include "bench/accel_stage.h"
#include "bench/bench.h"
#include "common/scene/analytic_scenes.h"
#include "cpu/cpu_backend.h"
#include "cpu/wide_bvh.h"

namespace pt::bench {

namespace {

using Clock = std::chrono::steady_clock;

struct Time {
  double cpu = 0.0, wall = 0.0;
};

template <class F> Time timed(F f) {
  const double c0 = process_cpu_seconds();
  const Clock::time_point w0 = Clock::now();
  f();
  return Time{process_cpu_seconds() - c0, std::chrono::duration<double>(Clock::now() - w0).count()};
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

// Medians of repeated timings of one quantity.
struct Samples {
  std::vector<double> cpu, wall;
  void add(Time t) { cpu.push_back(t.cpu), wall.push_back(t.wall); }
  Time med() const { return Time{median(cpu), median(wall)}; }
};

// work(first, last) over [0, n) in chunks on every core.
template <class F> void on_cores(std::size_t n, F work) {
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t a; (a = next.fetch_add(256)) < n;) work(a, std::min(n, a + 256));
  };
  std::vector<std::thread> pool;
  for (unsigned i = 1; i < cores(); i++) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
}

// The CPU's model name (/proc/cpuinfo), for the run file.
std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos) {
      std::string name = line.substr(line.find(':') + 1);
      return name.erase(0, name.find_first_not_of(" \t"));
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

// builtin:furnace_mesh seen from `view`: inside (its own camera at the centre), outside
// (from 3 radii away, the sphere filling the frame), grazing (inside, 0.1 from the wall,
// looking along it: half the rays meet the wall at a glancing angle).
Scene furnace_view(const std::string& view) {
  Scene s = analytic::make_furnace_mesh({});
  CameraDesc c = s.camera ? *s.camera : CameraDesc{};
  if (view == "outside") c.to_world = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 3.0f)), c.yfov = 0.75f;
  if (view == "grazing") c.to_world = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -0.9f, 0.0f));
  s.camera = c;
  return s;
}

struct Csv {
  std::ofstream out;
  std::string stage, view;
  std::size_t triangles = 0;
  RenderSettings s;
  // One row: `rays` rays in `t`; ratio: Embree's CPU time on the same rays over this one's.
  void row(const std::string& quantity, std::size_t rays, Time t, int runs, double embree_cpu, const std::string& note = "") {
    const double rate = rays && t.cpu > 0.0 ? double(rays) / t.cpu * cores() / 1e6 : 0.0;
    const double ratio = embree_cpu > 0.0 && t.cpu > 0.0 ? embree_cpu / t.cpu : 0.0;
    const double ns = 1e9 * t.cpu / (double(s.width) * double(s.height) * double(s.spp));
    out << stage << "," << view << "," << triangles << "," << s.width << "," << s.height << "," << s.spp << ","
        << quantity << "," << rays << "," << fixed(t.cpu, 4) << "," << fixed(t.wall, 4) << "," << runs << ","
        << fixed(ns, 1) << "," << (rate > 0.0 ? fixed(rate, 3) : "") << "," << (ratio > 0.0 ? fixed(ratio, 3) : "")
        << ",\"" << note << "\"\n";
    std::printf("  %-6s %-8s %-19s %8zu rays  cpu %7.3f s (%7.1f ns/sample)  wall %7.3f s  %6s M rays/s by CPU  %5s of Embree%s%s\n",
                stage.c_str(), view.c_str(), quantity.c_str(), rays, t.cpu, ns, t.wall,
                rate > 0.0 ? fixed(rate, 3).c_str() : "-", ratio > 0.0 ? fixed(ratio, 3).c_str() : "-",
                note.empty() ? "" : "  ", note.c_str());
    std::fflush(stdout);
  }
};

// Traces `rays` on all cores with the BVH's walk (as the stage's kernel walks it) or Embree.
Time trace_bvh(const Scene& scene, const Bvh& bvh, const WideBvh& wide, const RaySet& rays, std::vector<float>& t) {
  t.assign(rays.size(), kMiss);
  bind_cpu_scene(scene, &bvh, nullptr, 0, &wide), set_cpu_accel(true);
  return timed([&] { on_cores(rays.size(), [&](std::size_t a, std::size_t b) { trace_cpu(rays, nullptr, a, b, t.data()); }); });
}
Time trace_embree(const EmbreeScene& e, const RaySet& rays, std::vector<float>& t) {
  t.assign(rays.size(), kMiss);
  return timed([&] { on_cores(rays.size(), [&](std::size_t a, std::size_t b) { e.trace(rays, a, b - a, t.data()); }); });
}

std::size_t differing(const std::vector<float>& a, const std::vector<float>& b) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.size(); i++) {
    const bool inf_a = a[i] == kMiss, inf_b = b[i] == kMiss;
    if (inf_a != inf_b || (!inf_a && std::fabs(a[i] - b[i]) > 1e-5f * std::max(a[i], b[i]))) n++;
  }
  return n;
}

// The stage's render, timed: without the BVH's build (handed one) or with it.
Time render_timed(Backend& backend, const Scene& scene, const RenderSettings& s, const Bvh* bvh) {
  RenderHooks h;
  h.bvh = bvh;
  return timed([&] { render(backend, scene, s, h); });
}

// One stage on one view: the render and the same rays through the walk and Embree.
void measure(Csv& csv, const std::string& stage, const std::string& view, const RenderSettings& s, int rounds) {
  const Scene scene = furnace_view(view);
  csv.stage = stage, csv.view = view, csv.triangles = scene.triangles.size(), csv.s = s;
  std::optional<Bvh> bvh;
  const Time build = timed([&] { bvh.emplace(build_bvh(scene.triangles)); });
  WideBvh wide;
  const Time collapse = timed([&] { wide = build_wide_bvh(*bvh, scene.triangles); });
  std::optional<EmbreeScene> embree;
  Time embree_build;
  if (EmbreeScene::available()) embree_build = timed([&] { embree.emplace(scene.triangles, cores()); });
  Backend& backend = backend_for(stage, "cpu");
  // The ray sets: stage1's camera rays, or every ray stage4 traces, by kind.
  std::vector<RaySet> sets;
  std::vector<std::string> names;
  if (stage == "stage1") {
    sets.push_back(stage_camera_rays(scene, s)), names.push_back("camera");
  } else {
    const glm::vec3 eye = make_frame_params(scene, s).camera.origin;
    sets.resize(4), names = {"camera", "bounce", "shadow", "shadow_any"};
    sets[3].any_hit = true;
    for (const LoggedRay& r : stage4_rays(scene, s, *bvh)) {
      const int k = r.any_hit ? 3 : r.t_max < kNoBound ? 2 : r.origin == eye ? 0 : 1;
      sets[k].origins.push_back(r.origin), sets[k].dirs.push_back(r.dir);
      if (k >= 2) sets[k].t_max.push_back(r.t_max);
    }
  }
  std::size_t all_rays = 0;
  for (const RaySet& r : sets) all_rays += r.size();
  // Alternating rounds: the render without the build (the CPU's wide tree counted as part of
  // the build and handed over; then handed only the binary tree, set_scene collapsing it, as
  // round one of issue 50 measured), then each set by the walk and Embree.
  Samples render_no_build, render_collapsing, set_scene_time, collapse_in_set_scene;
  std::vector<Samples> walk(sets.size()), emb(sets.size());
  std::vector<float> t_walk, t_emb;
  std::vector<std::size_t> differ(sets.size(), 0);
  for (int round = 0; round < rounds; round++) {
    give_cpu_wide_bvh(backend, &*bvh, &wide);
    render_no_build.add(render_timed(backend, scene, s, &*bvh));
    set_scene_time.add(timed([&] { backend.set_scene(scene, scene_feature_mask(scene, s.sky), &*bvh); }));
    give_cpu_wide_bvh(backend, nullptr, nullptr);
    render_collapsing.add(render_timed(backend, scene, s, &*bvh));
    collapse_in_set_scene.add(timed([&] { backend.set_scene(scene, scene_feature_mask(scene, s.sky), &*bvh); }));
    for (std::size_t k = 0; k < sets.size(); k++) {
      if (sets[k].size() == 0) continue;
      walk[k].add(trace_bvh(scene, *bvh, wide, sets[k], t_walk));
      if (embree) emb[k].add(trace_embree(*embree, sets[k], t_emb)), differ[k] = differing(t_walk, t_emb);
    }
  }
  const Time with_build = render_timed(backend, scene, s, nullptr);
  // The film's share: its sums over the passes of the render's schedule.
  std::vector<glm::vec4> pass(std::size_t(s.width) * std::size_t(s.height), glm::vec4(0.5f));
  Film film(s.width, s.height);
  if (s.sampler == kSamplerSobol) film.track_halves(0);
  const Time film_time = timed([&] {
    for (std::uint64_t first = 0; first < s.spp; first = std::min<std::uint64_t>(pass_end(first), s.spp))
      film.add_pass(pass, std::min<std::uint64_t>(pass_end(first), s.spp) - first);
  });
  double embree_all = 0.0, walk_all = 0.0;
  for (std::size_t k = 0; k < sets.size(); k++) embree_all += emb[k].med().cpu, walk_all += walk[k].med().cpu;
  csv.row("build_bvh", 0, build, 1, 0.0, "build_bvh(), the binary tree");
  csv.row("collapse_wide", 0, collapse, 1, 0.0, "build_wide_bvh(), the CPU's 8-wide tree, part of the build");
  if (embree) csv.row("embree_build", 0, embree_build, 1, 0.0, "RTC_BUILD_QUALITY_HIGH, " + std::to_string(cores()) + " threads");
  csv.row("render_no_build", all_rays, render_no_build.med(), rounds, embree_all,
          "render() handed the BVH and its wide form: set_scene, passes, film");
  csv.row("render_collapsing", all_rays, render_collapsing.med(), rounds, embree_all,
          "render() handed the binary BVH only: set_scene collapses it");
  csv.row("render_with_build", all_rays, with_build, 1, embree_all, "render() building the BVH");
  csv.row("set_scene", 0, set_scene_time.med(), rounds, 0.0, "the CPU backend's set_scene handed the wide tree");
  csv.row("set_scene_collapsing", 0, collapse_in_set_scene.med(), rounds, 0.0, "the CPU backend's set_scene collapsing the tree");
  for (std::size_t k = 0; k < sets.size(); k++) {
    if (sets[k].size() == 0) continue;
    const std::string note = embree ? std::to_string(differ[k]) + " distances differ from Embree's" : "";
    csv.row("walk_" + names[k], sets[k].size(), walk[k].med(), rounds, emb[k].med().cpu, note);
    if (embree) csv.row("embree_" + names[k], sets[k].size(), emb[k].med(), rounds, emb[k].med().cpu);
  }
  // A sample's cost (CPU seconds over the render's samples): the camera rays, their
  // traversal (the walk alone on the stage's rays), the film, and the rest (shading,
  // the sampler's other numbers, the pixel loop) by difference.
  const double cam = stage == "stage1" ? camera_ray_seconds(scene, s) : 0.0;
  const double passes = render_no_build.med().cpu - set_scene_time.med().cpu - film_time.cpu;
  csv.row("cost_camera", 0, Time{cam, 0.0}, 1, 0.0, "sampler + camera_ray() alone, one thread");
  csv.row("cost_traversal", 0, Time{walk_all, 0.0}, rounds, 0.0, "the walk alone on the stage's rays");
  csv.row("cost_film", 0, film_time, 1, 0.0, "Film::add_pass over the render's passes");
  csv.row("cost_rest", 0, Time{passes - cam - walk_all, 0.0}, rounds, 0.0,
          "render minus set_scene, film, camera, traversal: shading, sampler, pixel loop");
  csv.row("cost_set_scene", 0, set_scene_time.med(), rounds, 0.0, "the backend's set_scene, once per render");
}

}  // namespace

void run_accel_stage(const Config& config) {
  const std::string load_before = load_average();
  const std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  Csv csv;
  csv.out = open_csv(config, "accel_stage.csv");
  csv.out << "stage,view,triangles,width,height,spp,quantity,rays,cpu_seconds,wall_seconds,runs,cpu_ns_per_sample,mrays_per_cpu_s,"
             "ratio_to_embree,note\n";
  const int rounds = std::max(1, config.stage_rounds);
  auto wanted = [&](const std::string& stage, const std::string& view) {
    const std::vector<std::string>& v = config.stage_views;
    return v.empty() || std::find(v.begin(), v.end(), stage + ":" + view) != v.end();
  };
  for (const char* view : {"inside", "outside", "grazing"}) {
    if (!wanted("stage1", view)) continue;
    RenderSettings s;
    s.width = s.height = config.stage_size, s.spp = 16, s.seed = config.seed;
    measure(csv, "stage1", view, s, rounds);
  }
  for (const char* view : {"inside", "outside"}) {
    if (!wanted("stage4", view)) continue;
    RenderSettings s;
    s.width = s.height = config.stage_size / 2, s.spp = 16, s.seed = config.seed;
    s.roulette = kRouletteThroughput;  // stage4's default
    measure(csv, "stage4", view, s, rounds);
  }
  std::ofstream run = open_csv(config, "accel_stage_run.txt");
  run << "date: " << date << "\ncommand: " << config.command << "\nload_before: " << load_before
      << "\nload_after: " << load_average() << "\nmachine: " << cpu_model() << "\nthreads: " << cores() << "\nrounds: " << rounds
      << "\nembree: " << (EmbreeScene::available() ? EmbreeScene::version() : EmbreeScene::missing_reason()) << "\n";
  std::printf("stage: wrote %s/accel_stage.csv and accel_stage_run.txt\n", config.out_dir.c_str());
}

}  // namespace pt::bench
