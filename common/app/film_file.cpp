// The film as a file (film_file.h): what identifies a render, the sample ranges, reading a
// part back from its .exr and adding parts of one render up.
#include "common/app/film_file.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <memory>


#include "common/app/checkpoint.h"
#include "common/app/exr_file.h"
#include "common/base/error.h"
#include "common/scene/scene.h"

namespace pt {

const char* const kFilmSumChannels[4] = {"R", "G", "B", "YY"};
const char* const kFilmHalfChannel = "Yhalf";

namespace {

[[noreturn]] void refuse(const std::string& path, const std::string& why) {
  throw Error(kExitBadScene, "'" + path + "' " + why);
}

std::string hex64(std::uint64_t v) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", (unsigned long long)v);
  return text;
}

std::string range_text(const SampleRange& r) { return std::to_string(r.first) + ":" + std::to_string(r.count); }

}  // namespace

std::string format_ranges(const std::vector<SampleRange>& ranges) {
  std::string text;
  for (const SampleRange& r : ranges) text += (text.empty() ? "" : ",") + range_text(r);
  return text;
}

std::vector<SampleRange> parse_ranges(const std::string& text, const std::string& where) {
  std::vector<SampleRange> ranges;
  std::size_t at = 0;
  while (at < text.size()) {
    std::size_t end = text.find(',', at);
    if (end == std::string::npos) end = text.size();
    const std::string item = text.substr(at, end - at);
    const std::size_t colon = item.find(':');
    unsigned long long first = 0, count = 0;
    int used = 0;
    if (colon == std::string::npos || std::sscanf(item.c_str(), "%llu:%llu%n", &first, &count, &used) != 2 ||
        used != int(item.size()) || count == 0) {
      refuse(where, "has a damaged sample range '" + item + "' in its pt:samples");
    }
    ranges.push_back({first, count});
    at = end + 1;
  }
  if (ranges.empty()) refuse(where, "holds no samples (its pt:samples is empty)");
  return ranges;
}

FilmIdentity film_identity(const char* stage, const Scene& scene, const RenderSettings& s) {
  FilmIdentity id;
  id.stage = stage;
  id.scene_hash = hex64(scene_hash(scene));
  // The camera as the kernel sees it depends on the image's aspect: hash its bytes.
  const Camera camera = make_camera(scene, float(s.width) / float(s.height));
  const std::uint64_t h = bytes_hash(&camera, sizeof camera);
  char text[256];
  std::snprintf(text, sizeof text, "%dx%d, sky %.9g,%.9g,%.9g, rr %s, depth cap %u, sampler %s, camera %s", s.width, s.height,
                double(s.sky.x), double(s.sky.y), double(s.sky.z), s.roulette == kRouletteThroughput ? "throughput" : "fixed",
                unsigned(s.depth_cap), s.sampler == kSamplerIndependent ? "independent" : "sobol", hex64(h).c_str());
  id.options = text;
  if (!s.mis_pilot) id.options += ", mis power";  // stage5 without its pilot (the others never run one)
  id.seed = s.seed;
  return id;
}

FilmPart read_film_part(const std::string& path) {
  ExrImage image;
  std::string why;
  if (!read_exr(path, image, why)) {
    refuse(path, "cannot be read as an .exr (" + why + "); give the .exr parts --out wrote");
  }
  return film_part_of(image, path);
}

FilmPart film_part_of(const ExrImage& image, const std::string& path) {
  auto text = [&](const char* name) {
    const std::string value = image.attribute(name);
    if (value.empty()) {
      refuse(path, std::string("has no ") + name +
                       ": it is not a part written by a stage's --out .exr (render the part again as .exr)");
    }
    return value;
  };
  FilmPart part;
  part.path = path;
  part.id.stage = text("pt:stage");
  part.id.scene_hash = text("pt:scene_hash");
  part.id.options = text("pt:options");
  const std::string seed = text("pt:seed");
  part.id.seed = std::uint32_t(std::strtoul(seed.c_str(), nullptr, 10));
  part.scene = image.attribute("pt:scene");
  part.backend = image.attribute("pt:backend");
  part.ranges = parse_ranges(text("pt:samples"), path);
  std::uint64_t spp = 0;
  for (const SampleRange& r : part.ranges) spp += r.count;
  // The sums, from the 32-bit halves of each double (a channel of another type or a
  // missing one: not a part).
  int index[8];
  for (int k = 0; k < 4; k++) {
    for (int half = 0; half < 2; half++) {
      const std::string name = std::string("film.") + kFilmSumChannels[k] + (half ? ".lo" : ".hi");
      const int c = image.channel(name);
      if (c < 0 || !image.is_uint[std::size_t(c)]) {
        refuse(path, "has no channel " + name + " of 32-bit integers: it is not a part written by a stage's --out .exr");
      }
      index[2 * k + half] = c;
    }
  }
  const std::size_t pixels = std::size_t(image.width) * std::size_t(image.height), n = image.channels.size();
  std::vector<double> sums(4 * pixels);
  for (std::size_t p = 0; p < pixels; p++) {
    const std::uint32_t* v = &image.pixels[p * n];
    for (int k = 0; k < 4; k++) sums[4 * p + std::size_t(k)] = join_double(v[index[2 * k]], v[index[2 * k + 1]]);
  }
  part.film = Film(image.width, image.height);
  part.film.restore(spp, std::move(sums));
  // The first half's luminance sums, where the render knew its halves (optional: without them,
  // or with an attribute that does not name the first half of this part's one range, the film
  // simply does not know them).
  const int hi = image.channel(std::string("film.") + kFilmHalfChannel + ".hi");
  const int lo = image.channel(std::string("film.") + kFilmHalfChannel + ".lo");
  const std::string halves = image.attribute("pt:halves");
  if (hi >= 0 && lo >= 0 && image.is_uint[std::size_t(hi)] && image.is_uint[std::size_t(lo)] &&
      part.ranges.size() == 1 && halves == format_ranges({{part.ranges.front().first, spp / 2}})) {
    std::vector<double> luminance(pixels);
    for (std::size_t p = 0; p < pixels; p++) luminance[p] = join_double(image.pixels[p * n + hi], image.pixels[p * n + lo]);
    part.film.restore_halves(spp / 2, std::move(luminance));
  }
  part.kept_halves = hi >= 0 && lo >= 0;
  return part;
}

FilmPart merge_film_parts(std::vector<FilmPart> parts, std::vector<std::string>& notes) {
  if (parts.empty()) throw Error(kExitBadOption, "no parts to merge");
  const FilmPart& ref = parts.front();
  auto differs = [&](const FilmPart& p, const char* field, const std::string& mine, const std::string& theirs) {
    if (mine != theirs) {
      refuse(p.path, std::string("is a part of another render: its ") + field + " is '" + mine + "', '" + ref.path +
                         "' has '" + theirs + "'; merge only parts of one render");
    }
  };
  for (const FilmPart& p : parts) {
    differs(p, "stage", p.id.stage, ref.id.stage);
    differs(p, "scene (content hash)", p.id.scene_hash, ref.id.scene_hash);
    differs(p, "options", p.id.options, ref.id.options);
    differs(p, "seed", std::to_string(p.id.seed), std::to_string(ref.id.seed));
    differs(p, "size", std::to_string(p.film.width()) + "x" + std::to_string(p.film.height()),
            std::to_string(ref.film.width()) + "x" + std::to_string(ref.film.height()));
    if (p.backend != ref.backend) {
      notes.push_back("'" + p.path + "' was rendered on " + p.backend + ", '" + ref.path + "' on " + ref.backend +
                      ": the merge equals one run to float rounding, not bit for bit");
    }
  }
  // Every range with the part that holds it, in sample order: no sample may be in two parts.
  struct Held {
    SampleRange range;
    std::size_t part;
  };
  std::vector<Held> held;
  for (std::size_t i = 0; i < parts.size(); i++) {
    for (const SampleRange& r : parts[i].ranges) held.push_back({r, i});
  }
  std::sort(held.begin(), held.end(), [](const Held& a, const Held& b) { return a.range.first < b.range.first; });
  std::vector<SampleRange> merged;
  for (std::size_t i = 0; i < held.size(); i++) {
    const SampleRange& r = held[i].range;
    if (i > 0) {
      const Held& before = held[i - 1];
      const std::uint64_t end = before.range.first + before.range.count;
      if (r.first < end) {
        refuse(parts[held[i].part].path, "holds samples " + range_text(r) + ", which overlap the samples " +
                                             range_text(before.range) + " of '" + parts[before.part].path +
                                             "'; merge parts with separate --samples ranges");
      }
      if (r.first > end) {
        notes.push_back("samples " + range_text({end, r.first - end}) +
                        " are in no part: the merge is an image of the samples it has");
      }
    }
    if (!merged.empty() && merged.back().first + merged.back().count == r.first) {
      merged.back().count += r.count;
    } else {
      merged.push_back(r);
    }
  }
  // The sums in the order of the parts' first samples, as one run adds its passes.
  std::vector<std::size_t> order(parts.size());
  for (std::size_t i = 0; i < order.size(); i++) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return parts[a].ranges.front().first < parts[b].ranges.front().first;
  });
  // Under the default sampler, parts that follow one another without a gap keep the two
  // halves of an aligned block known, for the per-pixel error (film.h, track_halves).
  bool follow = merged.size() == 1 && ref.id.options.find("sampler sobol") != std::string::npos;
  for (const FilmPart& p : parts) follow = follow && p.ranges.size() == 1;
  FilmPart out = parts[order[0]];
  for (const FilmPart& p : parts) out.kept_halves = out.kept_halves || p.kept_halves;
  // (One part keeps the halves it was read with.)
  if (follow && parts.size() > 1) out.film.track_halves(out.ranges.front().first);
  for (std::size_t k = 1; k < order.size(); k++) out.film.merge(parts[order[k]].film, follow);
  out.ranges = merged;
  out.path.clear();
  return out;
}

}  // namespace pt
