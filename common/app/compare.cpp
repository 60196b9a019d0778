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

double halves_upper_bound(double sum, double sum_of_squares) {
  if (!(sum > 0.0)) return std::numeric_limits<double>::infinity();  // halves that agree exactly tell nothing
  const double nu = sum * sum / sum_of_squares;  // Satterthwaite's degrees of freedom
  const double c = 2.0 / (9.0 * nu);
  const double root = 1.0 - c - kHalvesBoundZ * std::sqrt(c);  // Wilson-Hilferty, the lower quantile
  if (root <= 0.0) return std::numeric_limits<double>::infinity();
  return sum / (root * root * root);
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
  // Per pixel: the difference, each render's variance of one sample, the rounding allowance;
  // where both renders know the halves of their samples, each one's halves' variance of its mean.
  std::vector<double> d(pixels), var_a(pixels), var_b(pixels), rounding(pixels);
  const bool halves = c.halves = ref.has_halves() && test.has_halves();
  std::vector<double> half_a(halves ? pixels : 0), half_b(halves ? pixels : 0);
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
      if (halves) half_a[i] = ref.halves_variance(x, y), half_b[i] = test.halves_variance(x, y);
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
  // renders' one-sample variances (summed over its pixels), or where both renders know their
  // halves and it is smaller, the halves' upper bound, see compare.h. The image's difference
  // is the sum of the regions', its variance the sum of theirs, or the halves' bound over the
  // whole image where that is smaller.
  const int r = c.region = settings.region;
  const double n_a = double(ref.spp()), n_b = double(test.spp());
  // What a block of pixels sums: the differences, each render's one-sample variances, the
  // rounding allowance, each render's halves (their sum and sum of squares) and its largest
  // one-sample variance.
  struct Sums {
    double d = 0.0, s_a = 0.0, s_b = 0.0, rounding = 0.0, h_a = 0.0, h_a2 = 0.0, h_b = 0.0, h_b2 = 0.0;
    double top_a = 0.0, top_b = 0.0;
    void add(const Sums& o) {
      d += o.d, s_a += o.s_a, s_b += o.s_b, rounding += o.rounding;
      h_a += o.h_a, h_a2 += o.h_a2, h_b += o.h_b, h_b2 += o.h_b2;
      top_a = std::max(top_a, o.top_a), top_b = std::max(top_b, o.top_b);
    }
  };
  // The variance of the block's summed difference from the halves alone (infinity where they
  // cannot bound it): each render's bound, no smaller than the other render's scaled to this
  // one's spp (the guard of the larger variance, compare.h); and each render's figure, the
  // smaller of that and its share of the larger one-sample variance.
  const double inf = std::numeric_limits<double>::infinity();
  auto halves_bounds = [&](const Sums& k, double& g_a, double& g_b) {
    g_a = g_b = inf;
    if (!halves) return;
    // Not where one pixel holds more than kHalvesLargestShare of a render's sample variance:
    // its error may then be most of the block's, which its one degree of freedom cannot bound.
    const double u_a = k.top_a <= kHalvesLargestShare * k.s_a ? halves_upper_bound(k.h_a, k.h_a2) : inf;
    const double u_b = k.top_b <= kHalvesLargestShare * k.s_b ? halves_upper_bound(k.h_b, k.h_b2) : inf;
    g_a = std::max(u_a, u_b * n_b / n_a), g_b = std::max(u_b, u_a * n_a / n_b);
  };
  Sums image;
  double v_sum = 0.0;
  for (int y0 = 0; y0 < c.height; y0 += r) {
    for (int x0 = 0; x0 < c.width; x0 += r) {
      RegionTest t;
      t.x0 = x0, t.y0 = y0, t.x1 = std::min(x0 + r, c.width), t.y1 = std::min(y0 + r, c.height);
      Sums k;
      double ra = 0.0;
      for (int y = t.y0; y < t.y1; y++) {
        for (int x = t.x0; x < t.x1; x++) {
          const std::size_t i = std::size_t(y) * std::size_t(c.width) + std::size_t(x);
          k.d += d[i], k.s_a += var_a[i], k.s_b += var_b[i], k.rounding += rounding[i];
          ra += luminance(ref.mean(x, y));
          if (halves) {
            k.h_a += half_a[i], k.h_a2 += half_a[i] * half_a[i];
            k.h_b += half_b[i], k.h_b2 += half_b[i] * half_b[i];
            k.top_a = std::max(k.top_a, var_a[i]), k.top_b = std::max(k.top_b, var_b[i]);
          }
        }
      }
      const double s_max = std::max(k.s_a, k.s_b);
      double v_a = s_max / n_a, v_b = s_max / n_b, g_a, g_b;
      halves_bounds(k, g_a, g_b);
      if (g_a < v_a || g_b < v_b) c.halves_regions++;
      const double rv = std::min(v_a, g_a) + std::min(v_b, g_b) + k.rounding;
      const double count = double(t.x1 - t.x0) * double(t.y1 - t.y0);
      t.ref_mean = ra / count;
      t.difference = k.d / count;
      t.standard_error = std::sqrt(rv) / count;
      t.z = z_of(k.d, rv);
      c.regions.push_back(t);
      image.add(k);
      v_sum += rv;
    }
  }
  double g_a, g_b;
  halves_bounds(image, g_a, g_b);
  const double v_image = std::min(v_sum, g_a + g_b + image.rounding);
  c.mean_from_halves = v_image < v_sum;
  c.mean_standard_error = std::sqrt(v_image) / n;
  c.mean_t = z_of(image.d, v_image);
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
