// Adding parts of one render up (film_file.h, merge_film_parts): parts of another render
// and samples held twice are refused, gaps noted, and the sums added in the order one run
// adds its passes, so that parts split at the pass ends merge into that run's image bit for bit.
// Not in the article: the machinery of parts and merges (the contract (README.md), "Parts,
// merging and comparing").
#include "common/app/film_file.h"

#include <algorithm>
#include <string>
#include <vector>

#include "common/app/film_text.h"
#include "common/base/error.h"

namespace pt {

using film_text::addressable;
using film_text::range_text;
using film_text::refuse;
using film_text::shown;

FilmPart merge_film_parts(std::vector<FilmPart> parts, std::vector<std::string>& notes) {
  if (parts.empty()) throw Error(kExitBadOption, "no parts to merge");
  const FilmPart& ref = parts.front();
  auto differs = [&](const FilmPart& p, const char* field, const std::string& mine, const std::string& theirs) {
    if (mine != theirs) {
      refuse(p.path, std::string("is a part of another render: its ") + field + " is " + shown(mine, 200) + ", '" +
                         ref.path + "' has " + shown(theirs, 200) + "; merge only parts of one render");
    }
  };
  for (const FilmPart& p : parts) {
    // Ranges a render can hold, adding up to its film's count (film_part_of reads no other;
    // a part made in code is held to it too): no end or sum below can overflow.
    std::uint64_t count = 0;
    for (const SampleRange& r : p.ranges) {
      if (!addressable(r)) {
        refuse(p.path, "holds a sample range " + range_text(r) + " that is empty or goes past sample index " +
                           std::to_string(kSampleIndexLimit - 1) + "; render the part again");
      }
      count += r.count;
    }
    if (p.ranges.empty() || count != p.film.spp()) {
      refuse(p.path, "holds " + std::to_string(p.film.spp()) + " samples, but its sample ranges '" +
                         format_ranges(p.ranges) + "' hold " + std::to_string(count) + "; render the part again");
    }
    if (!p.checksummed) notes.push_back(unchecked_note(p));
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
