// Numerical stability of the kernels' building blocks at the extremes, compiled here as C++
// exactly as the CPU kernels compile them (common/shaders): rays spawned from 1000 random
// triangles with coordinates from 1e-8 to 1e8 never hit their own triangle again
// (spawn.glsl, the offsets that keep Eq. (2)-(5)'s next ray off the surface); GGX at
// incidence up to 89.99 degrees and alpha from 0 to 1 keeps f cos / pdf finite and <= 1
// (stage3's Eq. 4 weight); glass at grazing incidence and under total internal reflection
// has Fresnel in [0, 1] (1 under TIR) and no NaN; the film's means of radiance 1e-20 and
// 1e20 survive the float32 EXR output unchanged, down to float's subnormals.
#include <catch2/catch.hpp>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <random>
#include <unistd.h>

#include "common/render/film.h"
#include "common/app/image_output.h"
#include "common/scene/scene.h"
#include "cpu/kernel_prelude.h"

namespace {  // internal linkage: each test file compiles its own copy of the kernel code
namespace kernel {
#include "cpu/kernel_begin.h"
#include "common/kernel/rng.glsl"
#include "common/kernel/camera.glsl"
#include "common/kernel/intersect.glsl"
#include "common/kernel/sampling.glsl"
#include "common/kernel/bsdf.glsl"
#include "common/kernel/spawn.glsl"
#include "cpu/kernel_support.h"
}  // namespace kernel
using namespace pt;

// A unit vector uniform on the sphere.
glm::vec3 random_direction(std::mt19937& rng) {
  std::normal_distribution<float> g;
  glm::vec3 d;
  do d = glm::vec3(g(rng), g(rng), g(rng));
  while (glm::dot(d, d) < 1e-6f);
  return glm::normalize(d);
}

// A coordinate of magnitude 10^U(-8, 8) and either sign.
float random_coordinate(std::mt19937& rng) {
  std::uniform_real_distribution<float> e(-8.0f, 8.0f);
  return (rng() & 1u ? -1.0f : 1.0f) * std::pow(10.0f, e(rng));
}

struct SpawnStats {
  int triangles = 0, rays = 0, rehits = 0, camera_misses = 0;
};

// Shoots `rays` rays at random points of the triangle, and from each hit spawns a ray in a
// random direction (either side); counts the spawned rays that hit the triangle again.
void spawn_from(const pt::Triangle& tri, int rays, std::mt19937& rng, SpawnStats& stats) {
  glm::vec3 p0 = tri.p0, p1 = tri.p1, p2 = tri.p2;
  glm::vec3 c = glm::cross(p1 - p0, p2 - p0);
  if (!(glm::length(c) > 0.0f) || !std::isfinite(glm::length(c))) return;  // degenerate in float
  kernel::triangles = &tri;
  kernel::params.triangle_count = 1u;
  pt::Bounds b;
  b.extend(p0), b.extend(p1), b.extend(p2);
  kernel::params.scene_radius = std::max(0.5f * glm::length(b.hi - b.lo), 1e-30f);
  glm::vec3 n = glm::normalize(c);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  stats.triangles++;
  for (int i = 0; i < rays; i++) {
    // A point inside the triangle, seen from a random point on either side.
    float s = std::sqrt(u(rng)), t = u(rng);
    glm::vec3 q = (1.0f - s) * p0 + s * (1.0f - t) * p1 + s * t * p2;
    glm::vec3 from = random_direction(rng);
    if (glm::dot(from, n) == 0.0f) continue;
    float size = glm::length(b.hi - b.lo);
    kernel::Ray camera{q + size * from, -from};
    kernel::Hit hit = kernel::intersect_scene(camera, kernel::kInfinity);
    if (hit.kind == kPrimNone) {  // the target rounded onto or off an edge: not this test
      stats.camera_misses++;
      continue;
    }
    kernel::Surface surface = kernel::surface_at(camera, hit);
    glm::vec3 dir = random_direction(rng);
    kernel::Ray spawned = kernel::spawn_ray(surface.p, surface.n, dir);
    stats.rays++;
    if (kernel::intersect_scene(spawned, kernel::kInfinity).kind != kPrimNone) stats.rehits++;
  }
}

glm::vec3 incident(double degrees) {
  double t = degrees * M_PI / 180.0;
  return glm::vec3(float(std::sin(t)), 0.0f, float(std::cos(t)));
}

}  // namespace

TEST_CASE("stability: rays spawned from 1000 random triangles with coordinates 1e-8 to 1e8 never re-hit "
          "their surface", "[stability][spawn]") {
  // Each triangle 1e-6 to 1 times its distance from the origin across, that distance from
  // 1e-8 to 1e8: small features far from the origin, where ulps are coarse, and large ones
  // near it, where the offset is a fraction of the scene's size.
  std::mt19937 rng(2024);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  SpawnStats stats;
  for (int i = 0; i < 1000; i++) {
    glm::vec3 center = std::pow(10.0f, -8.0f + 16.0f * u(rng)) * random_direction(rng);
    float size = glm::length(center) * std::pow(10.0f, -6.0f + 6.0f * u(rng));
    pt::Triangle t{};
    t.p0 = center + size * random_direction(rng);
    t.p1 = center + size * random_direction(rng);
    t.p2 = center + size * random_direction(rng);
    spawn_from(t, 1000, rng, stats);
  }
  INFO(stats.triangles << " triangles, " << stats.rays << " rays, " << stats.rehits << " re-hits");
  CHECK(stats.triangles >= 950);  // only those that are degenerate in float are skipped
  CHECK(stats.rays >= 900000);
  CHECK(stats.rehits == 0);
}

TEST_CASE("stability: rays spawned from slivers with independent coordinates 1e-8 to 1e8 never re-hit them",
          "[stability][spawn]") {
  // Every coordinate of every vertex independent: slivers up to 1e8 long and 1e-8 wide.
  // The watertight test's t lost its sign for such triangles far from the ray origin, whatever
  // the offset, until hit_triangle() rejected every t within its own rounding bound
  // (intersect.glsl; docs/stability.md): 20,011 of 954,761 rays re-hit before that.
  std::mt19937 rng(2024);
  SpawnStats stats;
  for (int i = 0; i < 1000; i++) {
    pt::Triangle t{};
    t.p0 = glm::vec3(random_coordinate(rng), random_coordinate(rng), random_coordinate(rng));
    t.p1 = glm::vec3(random_coordinate(rng), random_coordinate(rng), random_coordinate(rng));
    t.p2 = glm::vec3(random_coordinate(rng), random_coordinate(rng), random_coordinate(rng));
    spawn_from(t, 1000, rng, stats);
  }
  INFO(stats.triangles << " triangles, " << stats.rays << " rays, " << stats.rehits << " re-hits");
  CHECK(stats.rays >= 800000);  // rays whose first hit is itself within rounding are not spawned
  CHECK(stats.rehits == 0);
}

TEST_CASE("stability: GGX from alpha 0 to 1 at incidence up to 89.99 degrees: f cos / pdf finite and <= 1",
          "[stability][ggx]") {
  pt::Material m = pt::make_metal(glm::vec3(1.0f), 0.5f);  // F0 = 1: the weight is G2 / G1
  kernel::rng_seed(1u, 2u, 3u);
  for (float alpha : {0.0f, 1e-9f, 0.5f * pt::kGgxMirrorAlpha, pt::kGgxMirrorAlpha, 1e-6f, 1e-4f, 1e-3f, 0.05f,
                      0.5f, 1.0f}) {
    m.kind = kMaterialConductor;
    m.alpha = alpha;
    uint lobe = kernel::choose_lobe(m, glm::vec3(0.0f, 0.0f, 1.0f), 0.5f);
    INFO("alpha " << alpha);
    if (alpha < pt::kGgxMirrorAlpha) {
      CHECK(lobe == kMaterialMirror);
      CHECK(kernel::is_delta_lobe(lobe));
      continue;
    }
    REQUIRE(lobe == kMaterialConductor);
    int bad = 0, below = 0;
    double worst = 0.0;
    for (double deg : {0.0, 45.0, 80.0, 89.0, 89.9, 89.99}) {
      glm::vec3 wo = incident(deg);
      for (int i = 0; i < 2000; i++) {
        kernel::LobeSample s = kernel::sample_lobe(lobe, m, wo, kernel::rng_next_vec2());
        if (s.wi.z <= 0.0f) {  // reflected below the surface: f = 0, the path ends
          below++;
          continue;
        }
        glm::vec3 f = kernel::eval_lobe(lobe, m, wo, s.wi);
        double w = double(f.x) * s.wi.z / s.pdf;
        if (!(s.pdf > 0.0f) || !std::isfinite(w) || !std::isfinite(s.pdf)) {
          bad++;
          continue;
        }
        worst = std::max(worst, w);
      }
    }
    INFO(bad << " non-finite weights, largest weight " << worst << ", " << below << " below the surface");
    CHECK(bad == 0);
    CHECK(worst <= 1.0 + 1e-4);
  }
}

TEST_CASE("stability: glass at grazing incidence and under total internal reflection: Fresnel in [0, 1], 1 "
          "under TIR, no NaN", "[stability][glass]") {
  pt::Material glass = pt::make_glass(glm::vec3(1.0f), 1.5f);
  for (float ior : {1.0f, 1.0001f, 1.5f, 3.0f}) {
    glass.ior = ior;
    for (double deg : {0.0, 30.0, 60.0, 89.0, 89.9, 89.99, 90.0}) {
      glm::vec3 wo = incident(deg);
      for (bool entering : {true, false}) {
        float eta = entering ? ior : 1.0f / ior;
        float F = kernel::fresnel_dielectric(wo.z, eta);
        double sin_t = std::sin(deg * M_PI / 180.0) / double(eta);
        INFO("ior " << ior << ", " << deg << " degrees, " << (entering ? "entering" : "leaving") << ": F = " << F);
        CHECK(F >= 0.0f);
        CHECK(F <= 1.0f);
        if (sin_t > 1.0) CHECK(F == 1.0f);                    // total internal reflection
        if (ior == 1.0f) CHECK(F == Approx(0.0).margin(1e-6));  // no interface at all
        if (deg == 89.99 && ior >= 1.5f && sin_t < 1.0) CHECK(F > 0.99f);  // grazing: nearly all reflects
        for (float u : {0.0f, 0.5f, 0.999999f}) {
          kernel::DeltaBounce b = kernel::sample_glass(glass, wo, entering, u);
          CHECK(std::isfinite(b.weight.x));
          CHECK(std::abs(glm::length(b.wi) - 1.0f) < 1e-5f);
          if (u < F) CHECK(b.wi.z == wo.z);  // reflected
          else CHECK(b.wi.z <= 0.0f);        // refracted to the other side
        }
      }
    }
  }
}

TEST_CASE("stability: radiance from 1e-20 to 1e20 goes through the film and the EXR file unchanged; float's "
          "edges are kept", "[stability][output]") {
  // The EXR is float32 (image_output.cpp): 1e-20 and 1e20 are exact there; so are float's
  // largest value and its smallest subnormal. (A half-float EXR would hold neither: its
  // range is 6e-8 (subnormal) to 65504.)
  const float values[] = {1e-20f, 1e20f, 1.0f, std::numeric_limits<float>::max(),
                          std::numeric_limits<float>::min(), std::numeric_limits<float>::denorm_min()};
  const int n = int(std::size(values));
  Film film(n, 1);
  std::vector<glm::vec4> pass;
  for (float v : values) pass.push_back(glm::vec4(v, v, v, v));  // one sample per pixel
  film.add_pass(pass, 1);
  std::vector<float> rgb = film.mean_rgb();
  for (int i = 0; i < n; i++) CHECK(rgb[3 * i] == values[i]);
  std::filesystem::path dir = std::filesystem::temp_directory_path() / ("pt_stability_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  std::string path = (dir / "edges.exr").string();
  pt::OutputFile(path).write(rgb, n, 1, pt::ImageMetadata{});
  auto in = OIIO::ImageInput::open(path);
  REQUIRE(in);
  std::vector<float> back(3 * n);
  REQUIRE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, back.data()));
  in->close();
  std::filesystem::remove_all(dir);
  for (int i = 0; i < n; i++) {
    INFO("value " << values[i]);
    CHECK(back[3 * i] == values[i]);
  }
}
