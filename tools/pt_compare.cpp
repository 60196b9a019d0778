// pt_compare: whether two renders of one scene agree within their noise (docs/film.md,
// "Comparing: pt_compare"). Each input is an .exr that a stage wrote with --out (its film:
// per-pixel sums and squared-luminance sums, common/app/film_file.h); the statistic is
// common/app/compare.h's: the image mean's t and every region's z (8x8-pixel blocks by
// default), each against the normal distribution at alpha / m (Bonferroni, m = regions +
// 1). Not in the article: a teacher's and a regression test's tool, resting on the
// article's estimators being means of independent samples, whose noise the film measures.
//   pt_compare [--alpha A] [--region PIXELS] [--zmap PATH.png|.exr] REF.exr TEST.exr
// Exit 0: consistent; 1: not consistent; 2: a bad option; 3: an input that cannot be
// compared (not a stage's .exr, fewer than 2 spp, another size, damaged or edited: its
// pt:checksum or its sample count disagrees, common/app/film_file.h); 5: --zmap not writable.
// An internal error exits 3 too, never 1, which would read as a verdict.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "common/app/compare.h"
#include "common/app/app.h"
#include "common/app/film_file.h"
#include "common/app/image_output.h"
#include "common/app/replace_file.h"
#include "common/base/error.h"

namespace {

// A per-pixel relative error above which two renders of different stages are noted as
// unsafe to compare (stage2 at 64 spp on the Cornell box, 1.5: 45 false alarms in 120
// against stage4; at 256 spp, 0.76: 1 in 20; docs/film.md).
constexpr double kHeavyNoise = 0.5;

const char* const kUsage =
    "usage: pt_compare [--alpha A] [--region PIXELS] [--zmap PATH] REF.exr TEST.exr (pt_compare --help)";

std::string describe(const pt::FilmPart& p) {
  return "'" + p.path + "' (" + p.id.stage + ", " + p.backend + ", " + std::to_string(p.film.spp()) + " spp, seed " +
         std::to_string(p.id.seed) + ")";
}

// "+0.45%" of `of`, or "" where the reference is black.
std::string percent(double difference, double of) {
  if (!(std::fabs(of) > 0.0)) return "";
  char text[48];
  std::snprintf(text, sizeof text, " (%+.3g%%)", 100.0 * difference / of);
  return text;
}

// The --zmap file, checked before the inputs are read: .png or .exr (an .hdr cannot hold
// the negative z), in a folder that takes it (exit 5, as --out's).
pt::OutputFile zmap_file(const std::string& path) {
  if (pt::OutputFile::is_exr(path) == false) {
    const std::size_t dot = path.rfind('.');
    std::string ext = dot == std::string::npos ? "" : path.substr(dot);
    for (char& ch : ext) ch = char(std::tolower((unsigned char)ch));
    if (ext != ".png") {
      throw pt::Error(pt::kExitBadOption, "--zmap '" + path + "': unknown type '" + ext +
                                              "'; use a name ending in .png (a picture) or .exr (the z values)");
    }
  }
  return pt::OutputFile(path, "--zmap");
}

int run(int argc, char** argv) {
  std::string ref_path, test_path, zmap_path;
  pt::CompareSettings settings;
  CLI::App app(
      "pt_compare: whether two renders of one scene agree within their noise, from the per-pixel variance "
      "that a stage's --out .exr carries, and under the default sampler from the halves of its samples where "
      "both renders know them (docs/film.md). Exit 0: consistent, 1: not consistent, 2: a bad option, 3: an "
      "input that cannot be compared (not a stage's .exr, under 2 spp, another size)",
      "pt_compare");
  app.add_option("--alpha", settings.alpha,
                 "the significance level: the chance that two unbiased renders are called not consistent "
                 "(Bonferroni-corrected over the regions and the mean)")
      ->capture_default_str()
      ->check(CLI::Range(1e-12, 0.5));
  app.add_option("--region", settings.region, "the side of the square regions tested one by one, in pixels")
      ->capture_default_str()
      ->check(CLI::Range(1, 65536));
  app.add_option("--zmap", zmap_path,
                 "also write a map of each pixel's z: .png red where TEST is brighter, blue where darker (full at "
                 "|z| = 4), the regions over the threshold outlined in yellow; .exr the values (R pixel z, G "
                 "region z, B 1 in a failed region)")
      ->type_name("PATH");
  app.add_option("REF", ref_path, "the reference render: an .exr written by a stage's --out, 2 spp or more")
      ->required();
  app.add_option("TEST", test_path, "the render to judge, of the same size (another seed, stage or backend)")
      ->required();
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::printf("%s", app.help().c_str());
    return 0;
  } catch (const CLI::ParseError& e) {
    std::string what = e.what();
    throw pt::Error(pt::kExitBadOption, what.substr(0, what.find('\n')) + "; " + kUsage);
  }
  std::optional<pt::OutputFile> zmap;
  if (!zmap_path.empty()) {
    zmap.emplace(zmap_file(zmap_path));
    for (const std::string& input : {ref_path, test_path}) {
      if (pt::same_file(zmap_path, input)) {
        throw pt::Error(pt::kExitBadOption, "--zmap '" + zmap_path + "' is the same file as the input '" + input +
                                                "'; give the z-map its own name");
      }
    }
  }

  const pt::FilmPart ref = pt::read_comparable(ref_path);
  const pt::FilmPart test = pt::read_comparable(test_path);
  pt::check_comparable(ref.film, "'" + ref_path + "'", test.film, "'" + test_path + "'");
  const pt::Comparison c = pt::compare_films(ref.film, test.film, settings);
  for (const pt::FilmPart* p : {&ref, &test}) {  // a part written before parts carried a checksum
    if (!p->checksummed) std::fprintf(stderr, "pt_compare: %s\n", pt::unchecked_note(*p).c_str());
  }

  std::printf("pt_compare: %s against %s, %dx%d, on luminance\n", describe(ref).c_str(), describe(test).c_str(),
              c.width, c.height);
  if (ref.id.scene_hash != test.id.scene_hash) {
    std::printf("note: the scenes differ (content hash %s, --scene '%s' against %s, '%s'): this asks whether two "
                "scenes give one image\n",
                ref.id.scene_hash.c_str(), ref.scene.c_str(), test.id.scene_hash.c_str(), test.scene.c_str());
  }
  if (ref.id.options != test.id.options) {
    std::printf("note: the options differ: reference '%s', test '%s'\n", ref.id.options.c_str(),
                test.id.options.c_str());
  }
  const double noisiest = std::max(ref.film.per_pixel_relative_error(), test.film.per_pixel_relative_error());
  if (ref.id.stage != test.id.stage && noisiest > kHeavyNoise) {
    std::printf("note: the stages differ and a render's per-pixel relative error is %.2g: so much noise can hide rare "
                "bright paths from its variance estimate, and shadowed regions then read too dark; render with more "
                "spp before trusting a NOT consistent (docs/film.md)\n",
                noisiest);
  }
  if (ref.id.seed == test.id.seed) {
    std::printf("note: both renders used seed %u, so their noise is not independent and the test is weaker; "
                "render the test with another --seed\n",
                unsigned(ref.id.seed));
  }
  std::printf("mean: ref %.6g test %.6g, difference %+.3g%s +- %.2g, t = %.3g\n", c.ref_mean, c.test_mean,
              c.test_mean - c.ref_mean, percent(c.test_mean - c.ref_mean, c.ref_mean).c_str(), c.mean_standard_error,
              c.mean_t);
  const pt::RegionTest& w = c.regions[c.worst];
  std::printf("worst region: pixels (%d,%d)-(%d,%d), difference %+.3g%s +- %.2g, z = %.3g; %d of %zu regions over "
              "the threshold\n",
              w.x0, w.y0, w.x1 - 1, w.y1 - 1, w.difference, percent(w.difference, w.ref_mean).c_str(),
              w.standard_error, w.z, c.failed_regions, c.regions.size());
  std::printf("threshold: |t|, |z| > %.3g (alpha %g, Bonferroni over %d tests: %zu regions of %dx%d pixels and the "
              "mean)\n",
              c.threshold, settings.alpha, c.tests, c.regions.size(), c.region, c.region);
  if (c.halves) {
    std::printf("variance: from the halves of the samples in %d of %zu regions%s, elsewhere from the samples' "
                "variance (docs/film.md)\n", c.halves_regions, c.regions.size(), c.mean_from_halves ? " and the mean" : "");
  }
  if (zmap) {
    pt::ImageMetadata meta;
    meta.stage = "pt_compare";
    meta.scene = test.scene;
    const bool exr = pt::OutputFile::is_exr(zmap->path());
    zmap->write(exr ? pt::zmap_values(c) : pt::zmap_picture(c), c.width, c.height, meta);
    std::printf("zmap: %s\n", zmap->path().c_str());
  }
  if (c.consistent) {
    std::printf("consistent: the renders agree within their noise (corrected p = %.2g, alpha %g)\n", c.p_value,
                settings.alpha);
    return 0;
  }
  std::string what = c.mean_failed ? "the mean" : "";
  if (c.failed_regions > 0) {
    what += std::string(what.empty() ? "" : " and ") + std::to_string(c.failed_regions) + " of " +
            std::to_string(c.regions.size()) + (c.regions.size() == 1 ? " region" : " regions");
  }
  const bool one = c.mean_failed ? c.failed_regions == 0 : c.failed_regions == 1;
  std::printf("NOT consistent: %s %s beyond their noise (corrected p = %.2g, alpha %g)\n", what.c_str(),
              one ? "differs" : "differ", c.p_value, settings.alpha);
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  return pt::run_guarded("pt_compare", [&] { return run(argc, argv); }, 3);
}
