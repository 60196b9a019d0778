// The environment map's table build alone (issue 49, "Measures", item 5): make_environment on a
// W x H map of deterministic, varied radiance, timed in wall and CPU seconds (best of N).
// Not part of the article: bench machinery; bench/env/README.md says how to build and run it:
//   bench/env/table_time 4096 2048 5   ->   "make_environment 4096x2048: wall_s=... cpu_s=..."
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <vector>

#include "common/scene/environment.h"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: table_time WIDTH HEIGHT REPEATS\n");
    return 2;
  }
  const unsigned w = unsigned(std::atoi(argv[1])), h = unsigned(std::atoi(argv[2]));
  const int repeats = std::atoi(argv[3]);
  if (w == 0 || h == 0 || repeats <= 0) {
    std::fprintf(stderr, "table_time: WIDTH, HEIGHT and REPEATS must be positive integers\n");
    return 2;
  }
  std::vector<float> rgb(size_t(w) * h * 3);
  for (size_t i = 0; i < rgb.size(); ++i) {  // a smooth sky with a few bright texels
    rgb[i] = 0.5f + 0.4f * std::sin(float(i % 977) * 0.01f) + ((i / 3) % 65537 == 0 ? 1.0e4f : 0.0f);
  }
  double best_wall = 1e30, best_cpu = 1e30;
  double checksum = 0;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();
    auto env = pt::make_environment("table_time", w, h, rgb, 1.0f, 0.0f);
    const std::clock_t c1 = std::clock();
    const auto t1 = std::chrono::steady_clock::now();
    checksum += env->mean_luminance;
    best_wall = std::min(best_wall, std::chrono::duration<double>(t1 - t0).count());
    best_cpu = std::min(best_cpu, double(c1 - c0) / CLOCKS_PER_SEC);
  }
  std::printf("make_environment %ux%u: wall_s=%.4f cpu_s=%.4f (best of %d; mean luminance %.4f)\n", w, h, best_wall,
              best_cpu, repeats, checksum / repeats);
  return 0;
}
