// Scenes and closed forms of the environment map's image tests (issue #49; beyond the
// article, whose sky is one colour; tests/stages/test_environment_images.cpp): maps made in
// memory, a Lambert floor and a mirror sphere, and a reference lookup of the map in double,
// written from the documented orientation (docs/environment.md), not from the kernel's code.
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "common/render/film.h"
#include "common/scene/environment.h"
#include "common/scene/scene.h"

namespace pt::test {

// A map of one radiance everywhere (what --sky L is), 8 x 4 texels.
inline std::shared_ptr<const Environment> constant_environment(glm::vec3 radiance, float rotate_degrees = 0.0f) {
  std::vector<float> rgb;
  for (int i = 0; i < 8 * 4; i++) rgb.insert(rgb.end(), {radiance.x, radiance.y, radiance.z});
  return make_environment("constant", 8, 4, rgb, 1.0f, rotate_degrees);
}

// A black map of width x height texels but for the patch of columns [x0, x0 + nx) and rows
// [y0, y0 + ny) (rows from the top), of radiance `radiance`.
struct Patch {
  int width, height;        // the map's texels
  int x0, y0, nx, ny;       // the patch's texels
  glm::vec3 radiance;
};

inline std::shared_ptr<const Environment> patch_environment(const Patch& p, float rotate_degrees = 0.0f) {
  std::vector<float> rgb(std::size_t(3) * p.width * p.height, 0.0f);
  for (int y = p.y0; y < p.y0 + p.ny; y++) {
    for (int x = p.x0; x < p.x0 + p.nx; x++) {
      float* t = &rgb[3 * (std::size_t(y) * p.width + x)];
      t[0] = p.radiance.x, t[1] = p.radiance.y, t[2] = p.radiance.z;
    }
  }
  return make_environment("patch", p.width, p.height, rgb, 1.0f, rotate_degrees);
}

// The radiance from world direction d (unit), as the documentation defines the lookup:
// Blender's Environment Texture with +Y up, u = 1/2 + atan2(z, x) / 2 pi, v = acos(y) / pi
// from the image's top, bilinear between texel centres (i + 1/2) / W, u wrapping, v
// clamped; --env-rotate R turns the lookup direction about +Y: (c x + s z, y, -s x + c z).
glm::dvec3 reference_radiance(const Environment& env, glm::dvec3 d);

// The irradiance the map gives a surface facing +Y (a floor), E = integral of L cos over the
// upper hemisphere, computed exactly from the texels (environment_scenes.cpp says how).
glm::dvec3 floor_irradiance(const Environment& env);

// A Lambert floor (y = 0, half-size 20, albedo `albedo`) under an orthographic camera at
// height 0.5 looking straight down, half-extent 1.5 (builtin:floor_light's floor and camera);
// the floor sees the whole upper hemisphere, so under a map every pixel is albedo E / pi.
inline Scene environment_floor(float albedo) {
  Scene s;
  uint floor = s.add_material(make_diffuse(glm::vec3(albedo)));
  const float h = 20.0f;
  add_quad(s, {-h, 0, h}, {h, 0, h}, {h, 0, -h}, {-h, 0, -h}, floor);  // facing +y
  s.camera = orthographic_down({0.0f, 0.5f, 0.0f}, 1.5f);
  build_light_table(s);
  return s;
}

// A mirror sphere (make_metal(1, 0): F = 1 at every angle) of radius 1 at the origin, seen by
// an orthographic camera on +Z looking down -Z with half-extent kMirrorView: screen point
// (sx, sy) in [-1, 1]^2 is the ray down -Z through (sx, sy) x kMirrorView.
constexpr double kMirrorView = 1.2;
inline Scene mirror_sphere() {
  Scene s;
  s.add_sphere(glm::vec3(0.0f), 1.0f, s.add_material(make_metal(glm::vec3(1.0f), 0.0f)));
  s.camera = orthographic_front(5.0f, float(kMirrorView));
  build_light_table(s);
  return s;
}

// What the camera ray through screen point (sx, sy) sees in mirror_sphere(): the mirror-
// reflection law, r = d - 2 (d . n) n with d = -Z, where the ray hits the sphere, else -Z.
inline glm::dvec3 mirror_sphere_direction(double sx, double sy) {
  const double x = sx * kMirrorView, y = sy * kMirrorView, rr = x * x + y * y;
  if (rr >= 1.0) return {0.0, 0.0, -1.0};
  const glm::dvec3 n(x, y, std::sqrt(1.0 - rr)), d(0.0, 0.0, -1.0);
  return d - 2.0 * glm::dot(d, n) * n;
}

// The screen point whose reflection looks along the unit direction `to` (not -Z): the
// sphere's normal there halves the angle between the view ray's reverse (+Z) and `to`.
inline glm::dvec2 mirror_sphere_point(glm::dvec3 to) {
  glm::dvec3 n = glm::normalize(to + glm::dvec3(0.0, 0.0, 1.0));
  return glm::dvec2(n.x, n.y) / kMirrorView;
}

// The largest relative difference between two images of the same size, any channel.
double largest_relative_difference(const Film& a, const Film& b);
// The RMS over pixels of each pixel's luminance error against the expected value, relative
// to the expected luminance: the error a user sees, measured against the closed form.
double measured_relative_error(const Film& film, glm::dvec3 expected);
// The batches merged into one film.
Film merged(const std::vector<Film>& batches);
// CHECKs mirror_sphere()'s image pixel by pixel against reference_radiance at the reflected
// directions, each pixel within Bernstein's bound for a sample at most patch_luminance.
void check_mirror_image(const Film& film, const Environment& env, double patch_luminance);

}  // namespace pt::test
