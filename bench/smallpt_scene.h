// pt_smallpt_reference's scene (bench/smallpt_reference.cpp, issue #18's yardstick): the
// double-precision vectors and random numbers, Kevin Beason's smallpt spheres and camera
// (smallpt_scene.cpp), and the path tracer that renders them (smallpt_radiance.cpp). Bench
// only: no test uses it.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace pt::bench::smallpt {

struct V3 {
  double x = 0, y = 0, z = 0;
};
inline V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator*(V3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
inline V3 operator*(V3 a, V3 b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
inline double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline V3 unit(V3 a) { return a * (1.0 / std::sqrt(dot(a, a))); }
inline double max3(V3 a) { return std::max(a.x, std::max(a.y, a.z)); }

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

struct Scene {
  std::vector<Sphere> spheres;
  V3 eye, forward, cx, cy;  // cx, cy: the image plane's full width and height at unit distance
  double start = 140.0;     // camera rays start this far along their (unnormalised) direction
};

// smallpt's scene at width x height; front_wall: its black wall at z = 170 (--open-front leaves
// it out, as builtin:smallpt does). scene.start is left at smallpt's 140 (--start sets it).
Scene smallpt_scene(int width, int height, bool front_wall);

// The radiance arriving along ray r; depth: the hits before this ray's origin.
V3 radiance(const Scene& scene, Ray r, int depth, Rng& rng);

}  // namespace pt::bench::smallpt
