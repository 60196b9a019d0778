// pt_bench's acceleration section (issue 17; accel.h): the build of the largest mesh, three
// times each, by build_bvh (common/scene/bvh.cpp, binned SAH) and by Embree's
// high-quality build (RTC_BUILD_QUALITY_HIGH) on all cores and on one, with the bytes per
// triangle each keeps; written to accel_build.csv. Issue 17's target: our load + build
// within 2x Embree's.
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "bench/accel.h"
#include "bench/bench.h"

namespace pt::bench {

// The build of the largest scene, three times each: build_bvh, Embree's high-quality
// build on all cores and on one.
void compare_builds(const Scene& scene, const Config& config) {
  std::ofstream csv = open_csv(config, "accel_build.csv");
  csv << "method,triangles,threads,best_s,runs_s,bytes_per_triangle,note\n";
  const std::size_t n = scene.triangles.size();
  std::printf("== build of %zu triangles (best of 3)\n", n);
  auto line = [&](const char* method, const std::string& threads, const std::vector<double>& runs, double bytes_per_tri,
                  const std::string& note) {
    std::ostringstream all;
    for (double s : runs) all << (all.tellp() > 0 ? " " : "") << fixed(s, 4);
    const double best = *std::min_element(runs.begin(), runs.end());
    csv << method << "," << n << "," << threads << "," << best << "," << all.str() << "," << bytes_per_tri << ",\""
        << note << "\"\n";
    std::printf("  %-18s %s thread(s): %.3f s (%s), %.1f B/triangle; %s\n", method, threads.c_str(), best, all.str().c_str(),
                bytes_per_tri, note.c_str());
  };
  std::vector<double> ours;
  double ours_bytes = 0.0;
  std::size_t nodes = 0;
  for (int i = 0; i < 3; i++) {
    Bvh bvh = build_bvh(scene.triangles);
    ours.push_back(bvh.stats.build_seconds), ours_bytes = bvh.stats.bytes_per_triangle(), nodes = bvh.nodes.size();
  }
  // build_bvh() decides its own threads: a large root's two subtrees at once (bvh.cpp).
  line("bvh_build", "1-2", ours, ours_bytes,
       "binned SAH; a large mesh's two root subtrees built at once on two threads (common/scene/bvh.cpp); " +
           std::to_string(nodes) + " nodes of 32 B and a 4-byte index per triangle; the kernels also read the "
           "48-byte triangles");
  if (!EmbreeScene::available()) {
    csv << "embree_hq,," << cores() << ",,,,\"" << EmbreeScene::missing_reason() << "\"\n";
    return;
  }
  for (unsigned threads : {cores(), 1u}) {
    std::vector<double> runs, commits;
    double bytes = 0.0;
    for (int i = 0; i < 3; i++) {
      EmbreeScene e(scene.triangles, threads);
      runs.push_back(e.build_seconds()), commits.push_back(e.commit_seconds());
      bytes = double(e.bytes()) / double(n);
    }
    line(threads == 1 && cores() > 1 ? "embree_hq_1thread" : "embree_hq", std::to_string(threads), runs, bytes,
         "rtcNewScene to rtcCommitScene, RTC_BUILD_QUALITY_HIGH (commit alone: best " +
             fixed(*std::min_element(commits.begin(), commits.end()), 4) +
             " s); bytes: what the commit kept (its BVH holds its own copy of the vertices)");
    if (cores() == 1) break;
  }
}

}  // namespace pt::bench
