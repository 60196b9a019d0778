// The film as a file: an .exr written by --out is an ordinary RGB image that also carries
// what merging it with other parts of the same render needs (the contract (README.md),
// "Parts, merging and comparing"): the film's per-pixel sums in full double precision, the
// estimated variance of each pixel, and metadata naming the stage, the scene's content,
// the image-changing options, the seed and the sample ranges it holds. pt_merge
// (tools/pt_merge.cpp) adds parts up. Not in the article: the article's estimators are
// sums of independent samples, which is what makes a frame splittable at all.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "common/render/film.h"
#include "common/render/render.h"

namespace pt {

struct ExrImage;
struct Scene;

// The samples FIRST ... FIRST + COUNT - 1 of every pixel.
struct SampleRange {
  std::uint64_t first = 0;
  std::uint64_t count = 0;
};

// "0:16,32:16", and back (throws pt::Error(kExitBadScene) naming `where` when malformed).
std::string format_ranges(const std::vector<SampleRange>& ranges);
std::vector<SampleRange> parse_ranges(const std::string& text, const std::string& where);

// What every part of one render shares: parts that differ in any of it are refused.
struct FilmIdentity {
  std::string stage;       // "stage4_direct_indirect"
  std::string scene_hash;  // the scene's content (scene_hash()), 16 hex digits
  std::string options;     // the options that change the image, as text ("64x64, sky 0,0,0, ...")
  std::uint32_t seed = 0;
};

FilmIdentity film_identity(const char* stage, const Scene& scene, const RenderSettings& settings);

// One part as read back from its .exr.
struct FilmPart {
  std::string path;
  FilmIdentity id;
  std::string scene;    // --scene as it was given (shown, not compared)
  std::string backend;  // "cpu (2 threads)", ...: parts of two backends agree to float rounding
  std::vector<SampleRange> ranges;
  Film film{1, 1};
  bool kept_halves = false;  // its .exr had the halves' channels (--keep-halves); a merge: any part's
};

// The EXR's channels: R, G, B (the mean radiance), Y.variance (the estimated variance of the
// pixel's mean luminance), then film.<S>.hi and film.<S>.lo for S in R, G, B, YY: the two
// 32-bit halves of each double sum, so a merge restores the sums bit for bit. With
// --keep-halves (ImageMetadata::keep_halves), a film that knows the halves of its samples
// (Film::has_halves) adds film.Yhalf.hi and .lo, the first half's luminance sums, and the
// attribute pt:halves, that half's range (FIRST:COUNT). Not by default: a merge of parts
// that do not split at the half cannot know them, and its .exr would then have fewer
// channels than the one-run's.
extern const char* const kFilmSumChannels[4];
extern const char* const kFilmHalfChannel;

// A double as the two 32-bit halves of its bits (the .hi and .lo channels), and back.
inline void split_double(double v, std::uint32_t& hi, std::uint32_t& lo) {
  std::uint64_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  hi = std::uint32_t(bits >> 32), lo = std::uint32_t(bits);
}
inline double join_double(std::uint32_t hi, std::uint32_t lo) {
  const std::uint64_t bits = (std::uint64_t(hi) << 32) | lo;
  double v;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

// Reads a part, or throws pt::Error(kExitBadScene) naming the file and what is missing.
FilmPart read_film_part(const std::string& path);
// The part an .exr already read holds (read_film_part without the reading).
FilmPart film_part_of(const ExrImage& image, const std::string& path);

// Adds parts of one render up, in the order of their first samples. Throws
// pt::Error(kExitBadScene) naming the file and the field for a part of another render
// (stage, scene, options, seed, size) or samples that two parts both hold; `notes` gets a
// line for each gap in the samples and for parts of different backends.
FilmPart merge_film_parts(std::vector<FilmPart> parts, std::vector<std::string>& notes);

}  // namespace pt
