// The environment map on the host (see environment.h): reading the image, and the tables of
// the piecewise-constant 2D distribution over it that common/kernel/environment.glsl samples
// (pbrt's PiecewiseConstant2D: a marginal distribution over rows, a conditional one per row).
// Beyond the article: issue #49, docs/environment.md.
#include "common/scene/environment.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <thread>

#include "common/base/error.h"
#include "common/base/openimageio.h"

namespace pt {

namespace {

double luminance_of(const float* rgb) {
  return 0.2126 * double(rgb[0]) + 0.7152 * double(rgb[1]) + 0.0722 * double(rgb[2]);
}

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Runs body(y0, y1) over the rows [0, h) in one block per core (a 4k x 2k map's tables
// took 0.43 s on one).
template <class Body>
void over_rows(std::size_t h, const Body& body) {
  const std::size_t threads = std::clamp<std::size_t>(std::thread::hardware_concurrency(), 1, 16);
  if (threads == 1 || h < 64) return body(std::size_t(0), h);
  std::vector<std::thread> pool;
  for (std::size_t t = 0; t < threads; t++) pool.emplace_back(body, h * t / threads, h * (t + 1) / threads);
  for (std::thread& th : pool) th.join();
}

}  // namespace

std::vector<float> environment_weights(const std::vector<float>& rgb, uint width, uint height) {
  const std::size_t w = width, h = height;
  // The bilinear lookup (environment_radiance_uv) spreads each texel over its neighbours'
  // cells: averaged over one cell, its neighbours weigh 1/8 and itself 6/8 along each axis
  // (u wraps around, v is clamped at the poles). So a texel is drawn wherever the lookup can
  // return light, and the sampling stays unbiased next to a single bright texel. The filter
  // is separable: along u first (each texel's luminance), then along v.
  std::vector<float> along_u(w * h);
  over_rows(h, [&](std::size_t y0, std::size_t y1) {
    std::vector<double> lum(w);
    for (std::size_t y = y0; y < y1; y++) {
      for (std::size_t x = 0; x < w; x++) lum[x] = luminance_of(&rgb[3 * (y * w + x)]);
      for (std::size_t x = 0; x < w; x++) {
        const double left = lum[x == 0 ? w - 1 : x - 1], right = lum[x + 1 == w ? 0 : x + 1];
        along_u[y * w + x] = float(0.125 * left + 0.75 * lum[x] + 0.125 * right);
      }
    }
  });
  std::vector<float> weights(w * h);
  over_rows(h, [&](std::size_t y0, std::size_t y1) {
    for (std::size_t y = y0; y < y1; y++) {
      // The row's solid angle per unit of v: the mean of sin(theta) over the row.
      const double theta0 = M_PI * double(y) / double(h), theta1 = M_PI * double(y + 1) / double(h);
      const double mean_sin = (std::cos(theta0) - std::cos(theta1)) / (theta1 - theta0);
      const float* up = &along_u[(y == 0 ? 0 : y - 1) * w];
      const float* row = &along_u[y * w];
      const float* down = &along_u[(y + 1 == h ? y : y + 1) * w];
      for (std::size_t x = 0; x < w; x++) {
        const double sum = 0.125 * double(up[x]) + 0.75 * double(row[x]) + 0.125 * double(down[x]);
        weights[y * w + x] = float(sum * mean_sin);
      }
    }
  });
  return weights;
}

std::shared_ptr<const Environment> make_environment(std::string name, uint width, uint height,
                                                    std::vector<float> rgb, float strength, float rotate_degrees) {
  auto env = std::make_shared<Environment>();
  env->path = std::move(name);
  env->width = width, env->height = height;
  env->strength = strength, env->rotate_degrees = rotate_degrees;
  const std::size_t w = width, h = height, n = w * h;
  std::size_t negative = 0;
  for (std::size_t i = 0; i < 3 * n; i++) {
    if (!std::isfinite(rgb[i])) {
      const std::size_t t = i / 3;
      throw Error(kExitBadScene, "--env '" + env->path + "': texel (" + std::to_string(t % w) + ", " +
                                     std::to_string(t / w) + ") is not a finite number; repair the image");
    }
    if (rgb[i] < 0.0f) rgb[i] = 0.0f, negative++;
    rgb[i] *= strength;
  }
  if (negative) {
    std::fprintf(stderr, "warning: --env '%s': %zu negative channel value(s) taken as 0 (radiance is never negative)\n",
                 env->path.c_str(), negative);
  }
  env->radiance = std::move(rgb);

  // The pdf over (u, v), normalised to integrate to 1 over the unit square.
  std::vector<float> f = environment_weights(env->radiance, width, height);
  // Per row: the sum of its weights, and its luminance times its solid angle (for the mean).
  std::vector<double> row_sum(h, 0.0), row_light(h, 0.0);
  over_rows(h, [&](std::size_t y0, std::size_t y1) {
    for (std::size_t y = y0; y < y1; y++) {
      const double solid = 2.0 * M_PI / double(w) *
                           (std::cos(M_PI * double(y) / double(h)) - std::cos(M_PI * double(y + 1) / double(h)));
      double lum = 0.0;
      for (std::size_t x = 0; x < w; x++) {
        row_sum[y] += double(f[y * w + x]);
        lum += luminance_of(&env->radiance[3 * (y * w + x)]);
      }
      row_light[y] = lum * solid;
    }
  });
  double total = 0.0, integral = 0.0;
  for (std::size_t y = 0; y < h; y++) total += row_sum[y], integral += row_light[y];
  // The mean luminance over the sphere: each texel's luminance times its solid angle.
  env->mean_luminance = integral / (4.0 * M_PI);
  const bool black = !(total > 0.0);
  env->table.resize(n + (h + 1) + h * (w + 1));
  // The rows' cumulative distribution, then each row's over its columns; the last entry of
  // each is exactly 1. A black map (or row) is uniform: nothing there is drawn anyway.
  float* marginal = env->table.data() + n;
  double c = 0.0;
  marginal[0] = 0.0f;
  for (std::size_t y = 0; y < h; y++) {
    c += black ? 1.0 / double(h) : row_sum[y] / total;
    marginal[y + 1] = float(std::min(c, 1.0));
  }
  marginal[h] = 1.0f;
  over_rows(h, [&](std::size_t y0, std::size_t y1) {
    for (std::size_t y = y0; y < y1; y++) {
      for (std::size_t x = 0; x < w; x++) {  // the pdf, normalised to a mean of 1
        env->table[y * w + x] = black ? 1.0f : float(double(f[y * w + x]) * double(n) / total);
      }
      float* row = env->table.data() + n + (h + 1) + y * (w + 1);
      double r = 0.0;
      row[0] = 0.0f;
      for (std::size_t x = 0; x < w; x++) {
        r += row_sum[y] > 0.0 ? double(f[y * w + x]) / row_sum[y] : 1.0 / double(w);
        row[x + 1] = float(std::min(r, 1.0));
      }
      row[w] = 1.0f;
    }
  });
  return env;
}

glm::vec2 environment_turn(const Environment& env) {
  // Whole turns first, exactly (fmod is exact), so that 450 is 90 and 1e30 is the turn its
  // remainder says, not the cosine of a radian count rounded to nothing.
  double degrees = std::fmod(double(env.rotate_degrees), 360.0);
  if (degrees < 0.0) degrees += 360.0;  // exact too: -270 is 90
  const double turn = degrees * M_PI / 180.0;
  return glm::vec2(float(std::cos(turn)), float(std::sin(turn)));
}

std::shared_ptr<const Environment> load_environment(const std::string& path, float strength, float rotate_degrees) {
  const std::string ext = lower(std::filesystem::path(path).extension().string());
  if (ext != ".hdr" && ext != ".exr") {
    throw Error(kExitBadOption, "--env '" + path +
                                    "' is not an .hdr or .exr file: an environment map is an equirectangular HDR "
                                    "image (Radiance .hdr or OpenEXR .exr)");
  }
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw Error(kExitBadScene, "--env '" + path + "': no such file; give the path of an .hdr or .exr image");
  }
  std::string why;
  const ImageCodec* codec = openimageio(why);
  if (!codec) throw Error(kExitBadScene, "--env '" + path + "' cannot be read: " + why);
  int width = 0, height = 0;
  std::vector<float> rgb;
  if (!codec->read_float_rgb(path, width, height, rgb, why)) {
    for (char& ch : why) ch = (ch == '\n' || ch == '\r') ? ' ' : ch;
    if (why.size() > 160) why = why.substr(0, 160) + "...";
    throw Error(kExitBadScene, "--env '" + path + "' cannot be read (" + why + "); give an intact .hdr or .exr image");
  }
  if (width < 2 || height < 1) {
    throw Error(kExitBadScene, "--env '" + path + "' is " + std::to_string(width) + " x " + std::to_string(height) +
                                   " texels: too small for a map of the sphere");
  }
  if (width != 2 * height) {
    std::fprintf(stderr, "warning: --env '%s' is %d x %d, not 2:1; it is read as equirectangular all the same\n",
                 path.c_str(), width, height);
  }
  return make_environment(path, uint(width), uint(height), std::move(rgb), strength, rotate_degrees);
}

}  // namespace pt
