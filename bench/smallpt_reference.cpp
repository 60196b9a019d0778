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
// The one documented difference of scene: smallpt has a black front wall at z = 170 behind
// the rays' start and builtin:smallpt leaves it out; this program has it by default
// (smallpt's scene) and drops it with --open-front. smallpt's 140-unit start also puts the
// top 0.5% of the image's rays above the ceiling, where they see the light sphere from
// outside (a bright top row); `--open-front --start 0` is builtin:smallpt's geometry (in double).
// A surface of albedo 0 (the light, the front wall) ends the path after its emission: all
// that could follow is multiplied by 0 (smallpt would trace on until its roulette).
//
//   pt_smallpt_reference --width 64 --height 48 --spp 256 --seed 1 --out out/ref.exr
//   pt_smallpt_reference --open-front --start 0 ...      # builtin:smallpt's geometry
//
// It writes a linear float RGB .exr, row 0 on top (as the stages' .exr), and prints one
// line with its CPU time (user + sys of the whole process, getrusage) and wall time.
#include <sys/resource.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "common/app/exr_file.h"

namespace {

struct V3 {
  double x = 0, y = 0, z = 0;
};
V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V3 operator*(V3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
V3 operator*(V3 a, V3 b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
V3 unit(V3 a) { return a * (1.0 / std::sqrt(dot(a, a))); }
double max3(V3 a) { return std::max(a.x, std::max(a.y, a.z)); }

// xoshiro256** (Blackman and Vigna), its state filled by splitmix64 from the seed and the
// pixel: every pixel has its own stream, so the image does not depend on the threads.
class Rng {
 public:
  Rng(uint64_t seed, uint64_t stream) {
    uint64_t x = seed * 0x9E3779B97F4A7C15ull ^ (stream + 0x632BE59BD9B4E019ull);
    for (uint64_t& w : s_) w = splitmix(x);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)

 private:
  static uint64_t splitmix(uint64_t& x) {
    uint64_t z = (x += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  static uint64_t rotl(uint64_t v, int k) { return (v << k) | (v >> (64 - k)); }
  uint64_t next() {
    const uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }
  uint64_t s_[4];
};

enum class Kind { Diffuse, Mirror, Glass };

struct Sphere {
  V3 centre;
  double radius;
  V3 albedo;  // diffuse albedo, the mirror's F0, the glass's transmission tint
  V3 emission;
  Kind kind;
};

struct Ray {
  V3 o, d;  // d unit length
};

// The nearest root t > kMinT of |o + t d - c| = r, or 0: the plain quadratic, as smallpt has
// it. In double, |o - c|^2 - r^2 beside the walls of radius 1e5 (1e10 - 1e10) keeps about
// 1e-6 absolute, far inside kMinT.
constexpr double kMinT = 1e-4;
double hit_sphere(const Sphere& s, const Ray& r) {
  const V3 oc = r.o - s.centre;
  const double b = dot(oc, r.d);
  const double c0 = dot(oc, oc) - s.radius * s.radius;
  const double disc = b * b - c0;
  if (disc < 0) return 0;
  const double root = std::sqrt(disc);
  const double near = -b - root, far = -b + root;
  if (near > kMinT) return near;
  if (far > kMinT) return far;
  return 0;
}

struct Scene {
  std::vector<Sphere> spheres;
  V3 eye, forward, cx, cy;  // cx, cy: the image plane's full width and height at unit distance
  double start = 140.0;     // camera rays start this far along their (unnormalised) direction
};

Scene smallpt_scene(int width, int height, bool front_wall) {
  Scene s;
  auto wall = [&](V3 c, V3 a) { s.spheres.push_back({c, 1e5, a, {}, Kind::Diffuse}); };
  wall({1e5 + 1, 40.8, 81.6}, {0.75, 0.25, 0.25});   // left
  wall({-1e5 + 99, 40.8, 81.6}, {0.25, 0.25, 0.75});  // right
  wall({50, 40.8, 1e5}, {0.75, 0.75, 0.75});          // back
  if (front_wall) wall({50, 40.8, -1e5 + 170}, {0, 0, 0});
  wall({50, 1e5, 81.6}, {0.75, 0.75, 0.75});          // bottom
  wall({50, -1e5 + 81.6, 81.6}, {0.75, 0.75, 0.75});  // top
  s.spheres.push_back({{27, 16.5, 47}, 16.5, {0.999, 0.999, 0.999}, {}, Kind::Mirror});
  s.spheres.push_back({{73, 16.5, 78}, 16.5, {0.999, 0.999, 0.999}, {}, Kind::Glass});
  s.spheres.push_back({{50, 681.6 - 0.27, 81.6}, 600, {}, {12, 12, 12}, Kind::Diffuse});
  s.eye = {50, 52, 295.6};
  s.forward = unit({0, -0.042612, -1});
  // The image plane at unit distance: 0.5135 high, width / height times that wide; cy is
  // "up" (perpendicular to the horizontal cx and to the view direction).
  const double plane_h = 0.5135;
  s.cx = {plane_h * width / height, 0, 0};
  s.cy = unit(cross(s.cx, s.forward)) * plane_h;
  return s;
}

bool intersect(const Scene& scene, const Ray& r, double& t, int& id) {
  t = 1e30;
  id = -1;
  for (int i = 0; i < static_cast<int>(scene.spheres.size()); ++i) {
    const double ti = hit_sphere(scene.spheres[i], r);
    if (ti > 0 && ti < t) {
      t = ti;
      id = i;
    }
  }
  return id >= 0;
}

// A cosine-distributed direction about the unit normal n (Duff et al.'s orthonormal basis).
V3 cosine_direction(V3 n, double u1, double u2) {
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  const double b = n.x * n.y * a;
  const V3 t1{1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x};
  const V3 t2{b, sign + n.y * n.y * a, -n.y};
  const double r = std::sqrt(u2), phi = 2.0 * M_PI * u1;
  return unit(t1 * (r * std::cos(phi)) + t2 * (r * std::sin(phi)) + n * std::sqrt(std::max(0.0, 1.0 - u2)));
}

V3 schlick(V3 f0, double cos_theta) {
  const double m = std::clamp(1.0 - cos_theta, 0.0, 1.0);
  const double m5 = m * m * m * m * m;
  return f0 + (V3{1, 1, 1} - f0) * m5;
}

// The radiance arriving along ray r; depth: the hits before this ray's origin.
V3 radiance(const Scene& scene, Ray r, int depth, Rng& rng) {
  V3 sum{}, weight{1, 1, 1};
  for (;;) {
    double t;
    int id;
    if (!intersect(scene, r, t, id)) return sum;  // black beyond the scene
    const Sphere& s = scene.spheres[id];
    const V3 x = r.o + r.d * t;
    const V3 n = unit(x - s.centre);
    const bool entering = dot(n, r.d) < 0;
    const V3 nl = entering ? n : n * -1.0;  // the normal on the side the ray came from
    sum = sum + weight * s.emission;
    const double p = max3(s.albedo);
    if (p <= 0) return sum;  // nothing more can be added through this surface
    if (++depth > 5) {       // Russian roulette from the 6th hit on
      if (rng.uniform() >= p) return sum;
      weight = weight * (1.0 / p);
    }
    if (s.kind == Kind::Diffuse) {
      weight = weight * s.albedo;
      const double u1 = rng.uniform(), u2 = rng.uniform();
      r = {x, cosine_direction(nl, u1, u2)};
      continue;
    }
    const double cos_i = -dot(r.d, nl);
    const Ray reflected{x, unit(r.d + nl * (2.0 * cos_i))};
    if (s.kind == Kind::Mirror) {
      weight = weight * schlick(s.albedo, cos_i);
      r = reflected;
      continue;
    }
    // Glass of index 1.5: eta = n_transmitted / n_incident; exact unpolarised Fresnel.
    const double eta = entering ? 1.5 : 1.0 / 1.5;
    const double cos2_t = (eta * eta - 1.0 + cos_i * cos_i) / (eta * eta);
    if (cos2_t <= 0) {  // total internal reflection
      r = reflected;
      continue;
    }
    const double cos_t = std::sqrt(cos2_t);
    const double r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    const double r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    const double F = 0.5 * (r_parl * r_parl + r_perp * r_perp);
    const Ray refracted{x, unit(r.d * (1.0 / eta) + nl * (cos_i / eta - cos_t))};
    if (depth <= 2) {  // the first two hits: both branches
      const V3 lr = radiance(scene, reflected, depth, rng);
      const V3 lt = radiance(scene, refracted, depth, rng);
      return sum + weight * (lr * F + s.albedo * lt * (1.0 - F));
    }
    const double P = 0.25 + 0.5 * F;  // deeper: one branch
    if (rng.uniform() < P) {
      weight = weight * (F / P);
      r = reflected;
    } else {
      weight = weight * s.albedo * ((1.0 - F) / (1.0 - P));
      r = refracted;
    }
  }
}

double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

}  // namespace

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
  app.add_flag("--open-front", open_front, "leave smallpt's black front wall out, as builtin:smallpt does");
  app.add_option("--start", start, "camera rays start this far ahead (times their unnormalised direction); "
                 "smallpt: 140, builtin:smallpt: 0")->check(CLI::Range(0.0, 1e4));
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
