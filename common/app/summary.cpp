// The summary line and the image's metadata of a finished render (app.h).
#include <cstdio>

#include "common/app/app.h"
#include "common/render/film.h"

namespace pt {

ImageMetadata image_metadata(const char* stage, const Options& o, const Backend& backend,
                             const RenderResult& r) {
  ImageMetadata m;
  m.stage = stage;
  m.backend = backend.kind() + " (" + backend.device_name() + ")";
  m.scene = o.scene;
  m.spp = r.film.spp();
  m.seed = o.render.seed;
  m.seconds = r.seconds;
  m.film = &r.film;  // an .exr carries the film and the samples it holds (film_file.h)
  if (r.film.spp() > 0) m.ranges = {{o.render.first_sample, r.film.spp()}};
  return m;
}

std::string summary_line(const char* stage, const Backend& backend, const RenderResult& r,
                         const std::string& tags) {
  const Film& f = r.film;
  double samples = double(f.width()) * double(f.height()) * double(f.spp());
  char line[512];
  std::snprintf(line, sizeof line, "%s: backend %s (%s), %dx%d, %llu spp, %.3f s, %.3g samples/s", stage,
                backend.kind().c_str(), backend.device_name().c_str(), f.width(), f.height(),
                (unsigned long long)f.spp(), r.seconds, r.seconds > 0.0 ? samples / r.seconds : 0.0);
  std::string s = line;
  if (f.spp() >= 2) {
    // The noise a user sees in a pixel, then the far smaller error of the image's mean.
    std::snprintf(line, sizeof line, ", estimated per-pixel relative error %.2g, image-mean error %.2g",
                  f.per_pixel_relative_error(), f.relative_standard_error());
    s += line;
  }
  // Events that are rare and deserve a word: each is said once, with its count.
  const RenderCounters& c = r.counters;
  if (c.non_finite) {
    std::uint32_t p = c.first_non_finite_pixel;
    s += ", " + std::to_string(c.non_finite) + " NaN/Inf samples dropped (first at pixel " +
         std::to_string(p % std::uint32_t(f.width())) + "," + std::to_string(p / std::uint32_t(f.width())) + ")";
  }
  if (c.zero_pdf) s += ", " + std::to_string(c.zero_pdf) + " paths ended by a zero pdf";
  if (c.depth_cap) s += ", " + std::to_string(c.depth_cap) + " paths stopped at the depth cap";
  if (!tags.empty()) s += " " + tags;
  if (r.bvh) s += " " + r.bvh->summary();
  if (!r.stage_note.empty()) s += " " + r.stage_note;
  return s;
}

}  // namespace pt
