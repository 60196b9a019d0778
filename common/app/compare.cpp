// Comparing two renders within their noise (see compare.h).
#include "common/app/compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>


#include "common/app/exr_file.h"
#include "common/base/error.h"
#include "common/base/srgb.h"

namespace pt {

namespace {

std::string size_text(const Film& f) { return std::to_string(f.width()) + "x" + std::to_string(f.height()); }

void check_usable(const Film& f, const std::string& name) {
  if (f.spp() < 2) {
    throw Error(kExitBadScene, name + " holds " + std::to_string(f.spp()) + (f.spp() == 1 ? " sample" : " samples") +
                                   " per pixel, so its per-pixel variance is unknown; render it again with --spp 2 "
                                   "or more (16 or more makes the comparison sharper)");
  }
  const std::vector<double>& s = f.sums();
  for (std::size_t i = 0; i < s.size(); i++) {
    if (!std::isfinite(s[i])) {
      const std::size_t p = i / 4;
      char where[64];
      std::snprintf(where, sizeof where, "(%d, %d)", int(p % std::size_t(f.width())), int(p / std::size_t(f.width())));
      throw Error(kExitBadScene, name + " has a pixel that is not a finite number, at " + where +
                                     ": it is not a usable render");
    }
  }
}

// The sRGB-encoded grey level g (0 to 1, clamped) as the linear value that OutputFile's PNG
// writer turns back into the code round(255 g): the picture's colours are linear in |z|.
float grey_level(double g) { return float(srgb_to_linear(std::clamp(g, 0.0, 1.0))); }

}  // namespace

FilmPart read_comparable(const std::string& path) {
  const std::string name = "'" + path + "'";
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw Error(kExitBadScene, name + " is not a file; give the .exr that a stage wrote with --out");
  }
  ExrImage image;
  std::string why;
  if (!read_exr(path, image, why)) {
    throw Error(kExitBadScene, name + " has no per-pixel variance: it cannot be read as an .exr (" + why +
                                   "); give the .exr that a stage wrote with --out NAME.exr and --spp 2 or more");
  }
  if (image.channel(std::string("film.") + kFilmSumChannels[3] + ".hi") < 0 || image.attribute("pt:stage").empty()) {
    throw Error(kExitBadScene, name + " has no per-pixel variance (the film's channels): it is not an .exr that a "
                                      "stage wrote with --out; render it again with --out NAME.exr and --spp 2 "
                                      "or more");
  }
  return film_part_of(image, path);
}

void check_comparable(const Film& ref, const std::string& ref_name, const Film& test, const std::string& test_name) {
  check_usable(ref, ref_name);
  check_usable(test, test_name);
  if (ref.width() != test.width() || ref.height() != test.height()) {
    throw Error(kExitBadScene, test_name + " is " + size_text(test) + " and " + ref_name + " is " + size_text(ref) +
                                   ": render both at the same --width and --height");
  }
}

double two_sided_p(double z) { return std::erfc(std::fabs(z) / std::sqrt(2.0)); }

double two_sided_threshold(double p) {
  if (!(p > 0.0)) return std::numeric_limits<double>::infinity();
  if (p >= 1.0) return 0.0;
  double lo = 0.0, hi = 40.0;  // two_sided_p falls from 1 at 0 to below 1e-300 at 40
  for (int i = 0; i < 200; i++) {
    const double mid = 0.5 * (lo + hi);
    (two_sided_p(mid) > p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

Comparison compare_films(const Film& ref, const Film& test, const CompareSettings& settings) {
  if (!(settings.alpha > 0.0 && settings.alpha < 1.0)) {
    throw Error(kExitBadOption, "--alpha must be between 0 and 1 (0.01: one false alarm in 100 comparisons)");
  }
  if (settings.region < 1) throw Error(kExitBadOption, "--region must be 1 pixel or more");
  check_comparable(ref, "the reference", test, "the test image");

  Comparison c;
  c.width = ref.width(), c.height = ref.height();
  const std::size_t pixels = std::size_t(c.width) * std::size_t(c.height);
  // Per pixel: the difference, each render's variance of one sample, the rounding allowance.
  std::vector<double> d(pixels), var_a(pixels), var_b(pixels), rounding(pixels);
  // The variance of a mean of spp samples of each render, per unit of one-sample variance.
  const double per_sample = 1.0 / double(ref.spp()) + 1.0 / double(test.spp());
  c.pixel_z.assign(pixels, 0.0f);
  for (int y = 0; y < c.height; y++) {
    for (int x = 0; x < c.width; x++) {
      const std::size_t i = std::size_t(y) * std::size_t(c.width) + std::size_t(x);
      const double a = luminance(ref.mean(x, y)), b = luminance(test.mean(x, y));
      const double r = kRoundingAllowance * std::max(std::fabs(a), std::fabs(b));
      d[i] = b - a;
      var_a[i] = ref.sample_variance(x, y), var_b[i] = test.sample_variance(x, y);
      rounding[i] = r * r;
      const double v = std::max(var_a[i], var_b[i]) * per_sample + rounding[i];
      c.pixel_z[i] = v > 0.0 ? float(d[i] / std::sqrt(v)) : 0.0f;
      c.ref_mean += a, c.test_mean += b;
    }
  }
  const double n = double(pixels);
  c.ref_mean /= n, c.test_mean /= n;
  auto z_of = [](double diff, double var) {
    if (var > 0.0) return diff / std::sqrt(var);
    return diff == 0.0 ? 0.0 : std::copysign(std::numeric_limits<double>::infinity(), diff);
  };

  // The regions; the variance of a region's summed difference takes the larger of the two
  // renders' one-sample variances (summed over its pixels), see compare.h. The image's
  // difference is the sum of the regions', its variance the sum of theirs.
  const int r = c.region = settings.region;
  double d_sum = 0.0, v_sum = 0.0;
  for (int y0 = 0; y0 < c.height; y0 += r) {
    for (int x0 = 0; x0 < c.width; x0 += r) {
      RegionTest t;
      t.x0 = x0, t.y0 = y0, t.x1 = std::min(x0 + r, c.width), t.y1 = std::min(y0 + r, c.height);
      double rd = 0.0, ra = 0.0, sa = 0.0, sb = 0.0, sr = 0.0;
      for (int y = t.y0; y < t.y1; y++) {
        for (int x = t.x0; x < t.x1; x++) {
          const std::size_t i = std::size_t(y) * std::size_t(c.width) + std::size_t(x);
          rd += d[i], sa += var_a[i], sb += var_b[i], sr += rounding[i];
          ra += luminance(ref.mean(x, y));
        }
      }
      const double rv = std::max(sa, sb) * per_sample + sr;
      const double count = double(t.x1 - t.x0) * double(t.y1 - t.y0);
      t.ref_mean = ra / count;
      t.difference = rd / count;
      t.standard_error = std::sqrt(rv) / count;
      t.z = z_of(rd, rv);
      c.regions.push_back(t);
      d_sum += rd, v_sum += rv;
    }
  }
  c.mean_standard_error = std::sqrt(v_sum) / n;
  c.mean_t = z_of(d_sum, v_sum);
  c.tests = int(c.regions.size()) + 1;
  c.threshold = two_sided_threshold(settings.alpha / double(c.tests));
  double most = std::fabs(c.mean_t);
  c.mean_failed = std::fabs(c.mean_t) > c.threshold;
  for (std::size_t k = 0; k < c.regions.size(); k++) {
    const double z = std::fabs(c.regions[k].z);
    if (z > c.threshold) c.failed_regions++;
    if (z > std::fabs(c.regions[c.worst].z)) c.worst = k;
    most = std::max(most, z);
  }
  c.consistent = !c.mean_failed && c.failed_regions == 0;
  c.p_value = std::min(1.0, double(c.tests) * two_sided_p(most));
  return c;
}

namespace {

// The region of each pixel, as an index into c.regions.
std::size_t region_of(const Comparison& c, int x, int y) {
  const int r = c.region, across = (c.width + r - 1) / r;
  return std::size_t(y / r) * std::size_t(across) + std::size_t(x / r);
}

}  // namespace

std::vector<float> zmap_picture(const Comparison& c) {
  std::vector<float> rgb(std::size_t(c.width) * std::size_t(c.height) * 3, 0.0f);
  for (int y = 0; y < c.height; y++) {
    for (int x = 0; x < c.width; x++) {
      const std::size_t i = std::size_t(y) * std::size_t(c.width) + std::size_t(x);
      const RegionTest& t = c.regions[region_of(c, x, y)];
      float* p = &rgb[3 * i];
      const bool edge = x == t.x0 || y == t.y0 || x == t.x1 - 1 || y == t.y1 - 1;
      if (std::fabs(t.z) > c.threshold && edge) {
        p[0] = p[1] = 1.0f;  // yellow: the outline of a region over the threshold
        continue;
      }
      const float level = grey_level(std::fabs(double(c.pixel_z[i])) / 4.0);
      (c.pixel_z[i] > 0.0f ? p[0] : p[2]) = level;
    }
  }
  return rgb;
}

std::vector<float> zmap_values(const Comparison& c) {
  std::vector<float> rgb(std::size_t(c.width) * std::size_t(c.height) * 3, 0.0f);
  for (int y = 0; y < c.height; y++) {
    for (int x = 0; x < c.width; x++) {
      const std::size_t i = std::size_t(y) * std::size_t(c.width) + std::size_t(x);
      const RegionTest& t = c.regions[region_of(c, x, y)];
      rgb[3 * i] = c.pixel_z[i];
      rgb[3 * i + 1] = float(t.z);
      rgb[3 * i + 2] = std::fabs(t.z) > c.threshold ? 1.0f : 0.0f;
    }
  }
  return rgb;
}

}  // namespace pt
