// pt_smallpt_reference: a plain double-precision CPU path tracer of Kevin Beason's smallpt
// scene with smallpt's algorithm, the yardstick of issue #18's efficiency comparison
// (bench/smallpt_compare.py, docs/results/smallpt_notes.md). Bench only: no test uses it.
//
// Written for this project from the algorithm's description, not from smallpt's code:
//   - camera rays through a uniformly jittered point of the pixel (a box filter, as the
//     stages do, common/kernel/camera.glsl; smallpt's 2x2 subpixels with a tent filter and
//     the clamp of each subpixel are not used), starting 140 units ahead of the camera;
//   - emission added at every hit (no light sampling), black where a ray leaves the scene;
//   - diffuse: one cosine-distributed direction, weight = albedo;
//   - Russian roulette only from the 6th hit on (after 5 bounces), continuing with
//     p = the surface's largest albedo component and dividing by p;
//   - glass: on the first two hits both reflection and refraction are followed (weighted by
//     F and 1 - F); deeper, one of them, reflection with probability 0.25 + 0.5 F;
//   - double precision throughout, std::thread over rows (2 threads by default).
//
// The scene's numbers, camera and radiometry are those of builtin:smallpt
// (common/scene/builtin_scenes.cpp): the same spheres, the camera at (50, 52, 295.6) looking
// along (0, -0.042612, -1) with an image plane 0.5135 high at unit distance, the light of
// radiance 12. Radiometry follows our materials (common/kernel/bsdf.glsl), not smallpt's:
// the mirror reflects Schlick's Fresnel with F0 = 0.999, glass uses the exact dielectric
// Fresnel (smallpt: Schlick's), its reflection is untinted and its transmission tinted
// 0.999 (smallpt tints both). The 1/eta^2 radiance scale of our glass is left out: every
// path that reaches the light leaves the ball as often as it enters it, so it cancels.
// builtin:smallpt is smallpt's scene: the black front wall at z = 170 and the camera's clip
// start of 140 (its rays start on that plane, common/kernel/camera.glsl); this program has
// both by default and drops them with --open-front and --start 0 (the open box that
// builtin:smallpt was until the camera had a clip start). smallpt's 140-unit start also
// puts the top 0.5% of the image's rays above the ceiling, where they see the light sphere
// from outside (a bright top row), in both.
// A surface of albedo 0 (the light, the front wall) ends the path after its emission: all
// that could follow is multiplied by 0 (smallpt would trace on until its roulette).
//
//   pt_smallpt_reference --width 64 --height 48 --spp 256 --seed 1 --out out/ref.exr
//   pt_smallpt_reference --open-front --start 0 ...      # the open box, rays from the eye
//
// It writes a linear float RGB .exr, row 0 on top (as the stages' .exr), and prints one
// line with its CPU time (user + sys of the whole process, getrusage) and wall time.
// This file: the options, the pixel loop over threads and the .exr; the scene is
// smallpt_scene.h and smallpt_scene.cpp, the path tracer smallpt_radiance.cpp.
#include <sys/resource.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "bench/smallpt_scene.h"
#include "common/app/exr_file.h"

namespace {

double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

}  // namespace

using pt::bench::smallpt::radiance;
using pt::bench::smallpt::Ray;
using pt::bench::smallpt::Rng;
using pt::bench::smallpt::Scene;
using pt::bench::smallpt::smallpt_scene;
using pt::bench::smallpt::unit;
using pt::bench::smallpt::V3;

int main(int argc, char** argv) {
  const auto wall_start = std::chrono::steady_clock::now();
  int width = 64, height = 48;
  unsigned spp = 256, threads = 2;
  uint64_t seed = 0;
  bool open_front = false;
  double start = 140.0;
  std::string out = "out/smallpt_reference.exr";
  CLI::App app{"pt_smallpt_reference: smallpt's algorithm on smallpt's scene, in double precision (issue #18's yardstick)"};
  app.add_option("--width", width, "image width in pixels")->check(CLI::Range(1, 65536));
  app.add_option("--height", height, "image height in pixels")->check(CLI::Range(1, 65536));
  app.add_option("--spp", spp, "samples per pixel")->check(CLI::Range(1u, 1u << 30));
  app.add_option("--seed", seed, "random seed");
  app.add_option("--threads", threads, "threads")->check(CLI::Range(1u, 1024u));
  app.add_option("--out", out, "output image (.exr: linear float RGB)");
  app.add_flag("--open-front", open_front, "leave smallpt's black front wall out (an open box)");
  app.add_option("--start", start, "camera rays start this far ahead (times their unnormalised direction); "
                 "smallpt and builtin:smallpt: 140")->check(CLI::Range(0.0, 1e4));
  CLI11_PARSE(app, argc, argv);

  Scene scene = smallpt_scene(width, height, !open_front);
  scene.start = start;
  std::vector<float> image(static_cast<size_t>(width) * height * 3);
  std::atomic<int> next_row{0};
  auto work = [&] {
    for (int y; (y = next_row.fetch_add(1)) < height;) {
      for (int x = 0; x < width; ++x) {
        const uint64_t pixel = static_cast<uint64_t>(y) * width + x;
        Rng rng(seed, pixel);
        V3 acc{};
        for (unsigned i = 0; i < spp; ++i) {
          // film position in [0,1)^2: x to the right, y downwards (row 0 on top)
          const double fx = (x + rng.uniform()) / width;
          const double fy = (y + rng.uniform()) / height;
          const V3 d = scene.cx * (fx - 0.5) + scene.cy * (0.5 - fy) + scene.forward;
          const Ray ray{scene.eye + d * scene.start, unit(d)};
          acc = acc + radiance(scene, ray, 0, rng);
        }
        float* px = &image[pixel * 3];
        px[0] = static_cast<float>(acc.x / spp);
        px[1] = static_cast<float>(acc.y / spp);
        px[2] = static_cast<float>(acc.z / spp);
      }
    }
  };
  std::vector<std::thread> pool;
  for (unsigned i = 1; i < threads; ++i) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();

  double mean[3] = {0, 0, 0};
  for (size_t i = 0; i < image.size(); ++i) mean[i % 3] += image[i];
  for (double& m : mean) m /= static_cast<double>(width) * height;

  // Written as the stages write theirs (common/app/exr_file.h), so both pay the same for it.
  pt::ExrImage exr;
  exr.width = width, exr.height = height;
  exr.channels = {"R", "G", "B"};
  exr.is_uint.assign(3, false);
  exr.pixels.resize(image.size());
  std::memcpy(exr.pixels.data(), image.data(), image.size() * sizeof(float));
  exr.text = {{"Software", "pt_smallpt_reference (bench/smallpt_reference.cpp)"},
              {"pt:spp", std::to_string(spp)},
              {"pt:seed", std::to_string(seed)},
              {"pt:scene", open_front ? "smallpt, open front" : "smallpt"}};
  std::string why;
  if (out.size() < 4 || out.substr(out.size() - 4) != ".exr" || !pt::write_exr(out, exr, why)) {
    std::fprintf(stderr, "pt_smallpt_reference: cannot write '%s': %s\n", out.c_str(),
                 why.empty() ? "give an .exr name" : why.c_str());
    return 1;
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  std::printf("pt_smallpt_reference: %dx%d, %u spp, seed %llu, %u threads%s, start %g: %.3f s wall, %.3f CPU s "
              "(user + sys, whole process); mean R %.5f G %.5f B %.5f -> %s\n",
              width, height, spp, static_cast<unsigned long long>(seed), threads, open_front ? ", open front" : "",
              start, wall, cpu_seconds(), mean[0], mean[1], mean[2], out.c_str());
  return 0;
}
