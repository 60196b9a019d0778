// The picture of a chi-square test: histogram, expected counts, residuals (see histogram_picture.h).
#include "tests/support/histogram_picture.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <vector>

#include "common/app/replace_file.h"
#include "common/base/error.h"
#include "common/base/openimageio.h"

namespace pt::test {

namespace {

const int kCell = 12;  // pixels per bin, each way
const int kGap = 6;    // pixels between the panels

}  // namespace

bool write_histogram_picture(const std::string& path, const Chi2Result& r, std::string& why) {
  if (r.theta_bins <= 0 || r.phi_bins <= 0 || r.observed.size() != std::size_t(r.theta_bins * r.phi_bins) ||
      r.expected.size() != r.observed.size()) {
    why = "the chi-square result holds no histogram";
    return false;
  }
  const ImageCodec* codec = openimageio(why);
  if (!codec) return false;
  const int panel_w = r.phi_bins * kCell, h = r.theta_bins * kCell, w = 3 * panel_w + 2 * kGap;
  std::vector<unsigned char> rgb(std::size_t(w) * h * 3, 64);  // the gaps: dark grey
  double top = 0.0;
  for (double e : r.expected) top = std::max(top, e);
  top = std::max(top, 1.0);
  for (int ti = 0; ti < r.theta_bins; ti++) {
    for (int pi = 0; pi < r.phi_bins; pi++) {
      const std::size_t bin = std::size_t(ti * r.phi_bins + pi);
      const double o = r.observed[bin], e = r.expected[bin];
      const double z = e > 0.0 ? (o - e) / std::sqrt(e) : (o > 0.0 ? 5.0 : 0.0);
      const double t = std::clamp(std::abs(z) / 5.0, 0.0, 1.0);
      const unsigned char grey_o = (unsigned char)std::lround(255.0 * std::clamp(o / top, 0.0, 1.0));
      const unsigned char grey_e = (unsigned char)std::lround(255.0 * std::clamp(e / top, 0.0, 1.0));
      const unsigned char fade = (unsigned char)std::lround(255.0 * (1.0 - t));
      const unsigned char colours[3][3] = {{grey_o, grey_o, grey_o},
                                           {grey_e, grey_e, grey_e},
                                           {z > 0.0 ? (unsigned char)255 : fade, fade,
                                            z > 0.0 ? fade : (unsigned char)255}};
      const int row0 = (r.theta_bins - 1 - ti) * kCell;  // cos theta = +1 at the top
      for (int panel = 0; panel < 3; panel++) {
        const int col0 = panel * (panel_w + kGap) + pi * kCell;
        for (int y = row0; y < row0 + kCell; y++) {
          for (int x = col0; x < col0 + kCell; x++) {
            const bool edge = y == row0 || x == col0;  // a thin grid between the bins
            for (int c = 0; c < 3; c++) {
              unsigned char v = colours[panel][c];
              rgb[(std::size_t(y) * w + x) * 3 + c] = edge ? (unsigned char)(v / 2 + 40) : v;
            }
          }
        }
      }
    }
  }
  ImageAttributes attributes = {
      {"ImageDescription",
       "left: samples per bin; middle: what the pdf expects; right: (observed - expected) / sqrt(expected), "
       "red too many, blue too few, full at 5. Rows: cos theta from +1 (top) to -1; columns: phi from 0 to 2 pi."}};
  std::vector<unsigned char> bytes;
  if (!codec->encode_rgb("png", w, h, rgb.data(), attributes, bytes, why)) return false;
  try {
    replace_file(path, {{bytes.data(), bytes.size()}}, "set PT_TEST_PICTURES to a writable folder");
    return true;
  } catch (const Error& e) {
    why = e.what();
    return false;
  }
}

std::string test_picture_path(const std::string& name) {
  const char* env = std::getenv("PT_TEST_PICTURES");
  std::filesystem::path folder = env && *env ? std::filesystem::path(env) : std::filesystem::path("test_pictures");
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  return (folder / name).string();
}

}  // namespace pt::test
