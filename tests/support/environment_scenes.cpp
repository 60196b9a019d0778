// The environment map image tests' scenes and checks (see environment_scenes.h; issue #49,
// beyond the article): the reference lookup in double, the floor's irradiance from the texels,
// and the mirror sphere's pixel check.
#include "tests/support/environment_scenes.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "tests/support/statistics.h"

namespace pt::test {

namespace {

// The map's texel (x, y) (rows from the top) in double.
glm::dvec3 reference_texel(const Environment& env, int x, int y) {
  const float* t = &env.radiance[3 * (std::size_t(y) * env.width + x)];
  return glm::dvec3(t[0], t[1], t[2]);
}

// The mean of the map's row y over its columns.
glm::dvec3 reference_row_mean(const Environment& env, int y) {
  glm::dvec3 sum(0.0);
  for (int x = 0; x < int(env.width); x++) sum += reference_texel(env, x, y);
  return sum / double(env.width);
}

// The bilinear weights in v: rows y0, y1 (clamped to the image) and the weight of y1.
struct RowWeights {
  int y0, y1;
  double t;
};
RowWeights reference_rows(const Environment& env, double v) {
  const int h = int(env.height);
  double fy = v * h - 0.5, y0f = std::floor(fy);
  int y0 = int(y0f);
  return {std::clamp(y0, 0, h - 1), std::clamp(y0 + 1, 0, h - 1), fy - y0f};
}

}  // namespace

// The radiance from world direction d (unit), as the documentation defines the lookup:
// Blender's Environment Texture with +Y up, u = 1/2 + atan2(z, x) / 2 pi, v = acos(y) / pi
// from the image's top, bilinear between texel centres (i + 1/2) / W, u wrapping, v
// clamped; --env-rotate R turns the lookup direction about +Y: (c x + s z, y, -s x + c z).
glm::dvec3 reference_radiance(const Environment& env, glm::dvec3 d) {
  const double r = double(env.rotate_degrees) * M_PI / 180.0, c = std::cos(r), s = std::sin(r);
  const glm::dvec3 m(c * d.x + s * d.z, d.y, -s * d.x + c * d.z);
  const double u = 0.5 + std::atan2(m.z, m.x) / (2.0 * M_PI), v = std::acos(std::clamp(m.y, -1.0, 1.0)) / M_PI;
  const int w = int(env.width);
  double fx = u * w - 0.5, x0f = std::floor(fx), tx = fx - x0f;
  int x0 = (int(x0f) % w + w) % w, x1 = (x0 + 1) % w;
  RowWeights rows = reference_rows(env, v);
  auto row = [&](int y) { return reference_texel(env, x0, y) * (1.0 - tx) + reference_texel(env, x1, y) * tx; };
  return row(rows.y0) * (1.0 - rows.t) + row(rows.y1) * rows.t;
}

// The irradiance the map gives a surface facing +Y (a floor), E = integral of L cos over the
// upper hemisphere, computed from the texels themselves: over u the bilinear lookup integrates
// in closed form to the bilinear blend of the rows' means (a piecewise-linear function that
// wraps averages to the mean of its samples); over v, dw = 2 pi^2 sin(pi v) du dv and
// cos = cos(pi v), composite Simpson on each piece between row centres (where the blend is
// linear: error below 1e-9 relative). A turn about +Y leaves E as it is.
glm::dvec3 floor_irradiance(const Environment& env) {
  auto integrand = [&](double v) {
    RowWeights rows = reference_rows(env, v);
    glm::dvec3 mean = reference_row_mean(env, rows.y0) * (1.0 - rows.t) + reference_row_mean(env, rows.y1) * rows.t;
    return mean * std::cos(M_PI * v) * std::sin(M_PI * v);
  };
  // The pieces: [0, 1/2] cut at the row centres (y + 1/2) / H.
  std::vector<double> cuts = {0.0};
  for (int y = 0; y < int(env.height); y++) {
    double c = (y + 0.5) / env.height;
    if (c < 0.5) cuts.push_back(c);
  }
  cuts.push_back(0.5);
  glm::dvec3 sum(0.0);
  const int n = 256;  // Simpson intervals per piece (even)
  for (std::size_t k = 0; k + 1 < cuts.size(); k++) {
    double a = cuts[k], h = (cuts[k + 1] - a) / n;
    glm::dvec3 piece = integrand(a) + integrand(cuts[k + 1]);
    for (int i = 1; i < n; i++) piece += (i % 2 == 1 ? 4.0 : 2.0) * integrand(a + i * h);
    sum += piece * h / 3.0;
  }
  return 2.0 * M_PI * M_PI * sum;
}

// The largest relative difference between two images of the same size.
double largest_relative_difference(const Film& a, const Film& b) {
  double worst = 0.0;
  for (int y = 0; y < a.height(); y++) {
    for (int x = 0; x < a.width(); x++) {
      glm::dvec3 va = a.mean(x, y), vb = b.mean(x, y);
      for (int c = 0; c < 3; c++) worst = std::max(worst, std::abs(va[c] - vb[c]) / std::max(std::abs(vb[c]), 1e-6));
    }
  }
  return worst;
}

// The RMS over pixels of each pixel's error against the expected value, relative to the
// expected image's mean luminance: the error a user sees, measured against the closed form.
double measured_relative_error(const Film& film, glm::dvec3 expected) {
  double sum = 0.0;
  for (int y = 0; y < film.height(); y++)
    for (int x = 0; x < film.width(); x++) sum += std::pow(luminance(film.mean(x, y)) - luminance(expected), 2.0);
  return std::sqrt(sum / (double(film.width()) * film.height())) / luminance(expected);
}

Film merged(const std::vector<Film>& batches) {
  Film all(batches.front().width(), batches.front().height());
  for (const Film& b : batches) all.merge(b);
  return all;
}

// The mirror sphere's image checked pixel by pixel against the reference lookup at the
// reflected directions. A pixel's sample is L(reflection of a jittered point): its mean and
// variance are known, from 16 x 16 points of the pixel, and its value is bounded by the
// patch's luminance M. Edge pixels see the patch's ramp on a sliver that n samples often
// miss, where the film's variance estimate is 0 and a z-test fails by chance, so each pixel
// is held to Bernstein's inequality, which holds for any bounded sample:
//   P(|mean - m| >= t) <= 2 exp(-n t^2 / (2 var + 2 M t / 3)), at Sidak's level per pixel.
// A patch in the wrong place, or half a texel off, is many t away (t < 0.03 M here).
void check_mirror_image(const Film& film, const Environment& env, double patch_luminance) {
  const int size = film.width(), k = 16;
  const double n = double(film.spp()), l = std::log(2.0 / sidak_alpha(1e-3, double(size) * size));
  const double M = patch_luminance;
  int failures = 0;
  double worst = 0.0;
  for (int y = 0; y < size; y++) {
    for (int x = 0; x < size; x++) {
      const double x0 = 2.0 * x / size - 1.0, y1 = 1.0 - 2.0 * y / size, step = 2.0 / size / k;
      double m = 0.0, m2 = 0.0;
      for (int j = 0; j < k; j++) {
        for (int i = 0; i < k; i++) {
          double v = luminance(reference_radiance(env, mirror_sphere_direction(x0 + (i + 0.5) * step,
                                                                              y1 - (j + 0.5) * step)));
          m += v / (k * k), m2 += v * v / (k * k);
        }
      }
      const double var = std::max(0.0, m2 - m * m);
      const double t = (M * l / 3.0 + std::sqrt(std::pow(M * l / 3.0, 2.0) + 2.0 * n * var * l)) / n;
      const double off = std::abs(luminance(film.mean(x, y)) - m), allowed = t + 1e-5 * m + 1e-7;
      worst = std::max(worst, off / allowed);
      if (off > allowed && failures++ < 10) {
        UNSCOPED_INFO("pixel " << x << "," << y << ": " << luminance(film.mean(x, y)) << ", want " << m << " +- "
                               << allowed);
      }
    }
  }
  INFO(failures << " pixels beyond their bound; the worst at " << worst << " of its bound");
  CHECK(failures == 0);
}

}  // namespace pt::test
