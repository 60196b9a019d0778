// A glTF file of one KHR_lights_punctual light above a white Lambert floor, seen straight
// down by an orthographic camera, its closed-form image, and the checks of stages 4 and 5
// against it on the backend under test: the light units and the hard-edged spot (issue #46).
// Not part of the article: punctual lights are deltas, in photometric units (683 lm/W).
#pragma once

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "common/render/render.h"
#include "common/scene/scene_loading.h"
#include "tests/support/cli_run.h"
#include "tests/support/gltf_writer.h"
#include "tests/support/image_checks.h"
#include "tests/support/lambert.h"
#include "tests/support/test_render.h"

namespace pt::test {

struct PhotometricFloor {
  std::string type = "point";  // "point", "spot" or "directional", pointing straight down
  double intensity = 683.0;    // candela (point, spot) or lux (directional): 683 is 1 W/sr, 1 W/m^2
  double inner = -1.0;         // a spot's cone angles (radians)
  double outer = -1.0;
  double height = 1.0;         // the light's height above the floor (y = 0)
  double view_half = 0.05;     // the camera's xmag = ymag, centred below the light
};

// Radiance of the white Lambert floor at (x, 0, z): (I / 683) cos / d^2 / pi under a point
// light, times the cone's step under a hard-edged spot (inner >= outer), (E / 683) / pi under
// a directional light at normal incidence.
inline double photometric_floor_radiance(const PhotometricFloor& f, double x, double z) {
  double watts = f.intensity / 683.0;
  if (f.type == "directional") return watts / M_PI;
  double d2 = x * x + z * z + f.height * f.height, cos_theta = f.height / std::sqrt(d2);
  if (f.type == "spot" && !(cos_theta >= std::cos(f.outer))) return 0.0;
  return watts * cos_theta / (M_PI * d2);
}

// Each pixel's mean of it; screen (sx, sy) sees the floor point (sx view, 0, -sy view). A
// spot's edge is a step: the quadrature runs on 16 x 16 cells of each pixel there.
inline ExpectedImage photometric_floor_image(const PhotometricFloor& f, int size) {
  return expected_image(size, size, [&](double x0, double y0, double x1, double y1) {
    auto radiance = [](double sx, double sy, const void* data) {
      const PhotometricFloor& f = *static_cast<const PhotometricFloor*>(data);
      return photometric_floor_radiance(f, sx * f.view_half, -sy * f.view_half);
    };
    return glm::dvec3(rect_average(x0, y0, x1, y1, radiance, &f, f.type == "spot" ? 16 : 1));
  });
}

// Writes the scene as a .gltf under the test's scratch folder and returns its path. The floor
// is white (base colour 1, metallic 0) with KHR_materials_specular's specularFactor 0, which
// leaves the glTF material's Lambert base alone; the light and the camera look down -Y.
inline std::string write_photometric_floor(const PhotometricFloor& f, const std::string& name) {
  GltfWriter g;
  int floor = g.diffuse(glm::vec3(1.0f));
  float h = 20.0f;
  g.node({{"mesh", g.quad({-h, 0, h}, {h, 0, h}, {h, 0, -h}, {-h, 0, -h}, floor)}});
  const nlohmann::json down = {-0.7071067811865476, 0.0, 0.0, 0.7071067811865476};  // -Z turned to -Y
  g.light_node(g.light(f.type, glm::vec3(1.0f), f.intensity, f.inner, f.outer),
               {{"translation", {0.0, f.height, 0.0}}, {"rotation", down}});
  std::string path = g.write((pt_test::scratch_dir("pt_photometric") / name).string());
  // The writer has no orthographic camera nor material extensions: added to its JSON here.
  nlohmann::json doc = nlohmann::json::parse(pt_test::read_file(path));
  doc["materials"][floor]["extensions"]["KHR_materials_specular"] = {{"specularFactor", 0.0}};
  doc["extensionsUsed"].push_back("KHR_materials_specular");
  doc["cameras"] = nlohmann::json::array(
      {{{"type", "orthographic"},
        {"orthographic", {{"xmag", f.view_half}, {"ymag", f.view_half}, {"znear", 0.01}, {"zfar", 100.0}}}}});
  doc["nodes"].push_back({{"camera", 0}, {"translation", {0.0, 0.5 * f.height, 0.0}}, {"rotation", down}});
  doc["scenes"][0]["nodes"].push_back(doc["nodes"].size() - 1);
  std::ofstream(path) << doc.dump(1) << "\n";
  return path;
}

// Renders the file in 8 batches of 64 spp (size x size) and checks every pixel and the
// image's mean against the closed form, with variance-derived tolerances (as
// analytic_suite.h's check_scene); returns all the samples in one film.
inline Film check_photometric_floor(const StageKernels& kernels, const PhotometricFloor& f, int size,
                                    const std::string& name, std::uint32_t seed) {
  INFO(f.type << " light of " << f.intensity << (f.type == "directional" ? " lux" : " cd"));
  Scene scene = load_scene(write_photometric_floor(f, name));
  RenderSettings s = settings(size, size, 64, seed);
  s.roulette = kRouletteThroughput;
  ExpectedImage expected = photometric_floor_image(f, size);
  std::vector<Film> batches = render_batches(kernels, scene, s, 8);
  Film all(size, size);
  for (const Film& b : batches) all.merge(b);
  CHECK(check_pixels(all, expected).passed());
  CHECK(channel_means_ratio(batches, expected) <= 1.0);
  return all;
}

// 683 cd at height 1: (683 / 683) cos 0 / (pi 1^2) = 1/pi straight below. The view is
// 0.1 wide, so each of the 8 x 8 pixels is within 0.8% of it; the middle four within 0.05%.
inline void check_photometric_point(const StageKernels& kernels, std::uint32_t seed) {
  PhotometricFloor f;
  CHECK(photometric_floor_radiance(f, 0.0, 0.0) == Approx(1.0 / M_PI).epsilon(1e-12));
  Film film = check_photometric_floor(kernels, f, 8, "point.gltf", seed);
  glm::dvec3 below = 0.25 * (film.mean(3, 3) + film.mean(4, 3) + film.mean(3, 4) + film.mean(4, 4));
  CHECK(below.x * M_PI == Approx(1.0).epsilon(1e-3));
  CHECK(below.y * M_PI == Approx(1.0).epsilon(1e-3));
  CHECK(below.z * M_PI == Approx(1.0).epsilon(1e-3));
}

// 683 lux straight down: 1/pi at every point of the floor, in every sample.
inline void check_photometric_sun(const StageKernels& kernels, std::uint32_t seed) {
  PhotometricFloor f;
  f.type = "directional";
  f.view_half = 1.0;
  Film film = check_photometric_floor(kernels, f, 8, "sun.gltf", seed);
  for (int y = 0; y < 8; y++) {
    for (int x = 0; x < 8; x++) {
      INFO("pixel " << x << "," << y);
      CHECK(film.mean(x, y).y * M_PI == Approx(1.0).epsilon(1e-5));
    }
  }
}

// A spot of 683 cd with inner == outer == 0.6 rad, 1 above the floor: a disc of radius
// tan 0.6 = 0.68 lit by cos / (pi d^2), nothing beyond; the view (2 x 2) holds its edge.
// Every pixel wholly outside the disc is exactly 0.
inline void check_hard_spot(const StageKernels& kernels, std::uint32_t seed) {
  PhotometricFloor f;
  f.type = "spot";
  f.inner = f.outer = 0.6;
  f.view_half = 1.0;
  const int size = 16;
  Film film = check_photometric_floor(kernels, f, size, "hard_spot.gltf", seed);
  int dark = 0, lit = 0;
  double edge = std::tan(f.outer) * f.height, pixel = 2.0 * f.view_half / size;
  for (int y = 0; y < size; y++) {
    for (int x = 0; x < size; x++) {
      // The pixel's nearest and farthest floor points from below the light.
      double x0 = -f.view_half + x * pixel, z0 = -f.view_half + y * pixel;
      double nx = std::max(0.0, std::max(x0, -(x0 + pixel))), nz = std::max(0.0, std::max(z0, -(z0 + pixel)));
      double fx = std::max(std::abs(x0), std::abs(x0 + pixel)), fz = std::max(std::abs(z0), std::abs(z0 + pixel));
      INFO("pixel " << x << "," << y);
      if (std::hypot(nx, nz) > edge) {
        dark++;
        CHECK(film.mean(x, y) == glm::dvec3(0.0));
      } else if (std::hypot(fx, fz) < edge) {
        lit++;
        CHECK(film.mean(x, y).y > 0.0);
      }
    }
  }
  CHECK(dark > 50);  // of 256: the corners
  CHECK(lit > 50);
}

}  // namespace pt::test
