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

// "0:16,32:16", and back: strictly, as format_ranges writes them (throws
// pt::Error(kExitBadScene) naming `where` and pt:samples when malformed, when a range is
// empty or ends past kSampleIndexLimit, or when the ranges do not ascend without overlap).
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
  bool checksummed = true;   // false: its .exr has no pt:checksum (written before parts carried one)
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

// A part's checksum, its text attribute pt:checksum (16 hex digits): the 64-bit FNV-1a hash
// of checkpoints (checkpoint.h) over the image's size, the attributes that say which render
// it is and which samples it holds (pt:stage, pt:scene_hash, pt:options, pt:seed,
// pt:samples, pt:halves), and every channel's name, type and pixels, bit for bit.
// OutputFile writes it with every film (exr_image() in image_output.cpp); stage and seed are
// the pt:stage and pt:seed texts, which OutputFile::write adds after exr_image(). It finds
// damage and edits; it is no signature: whoever edits a part can compute it again, and then
// only the sample-count checks of film_part_of stand.
extern const char* const kFilmChecksumAttribute;
std::string film_checksum(const ExrImage& image, const std::string& stage, const std::string& seed);

// Reads a part, or throws pt::Error(kExitBadScene) naming the file and what is missing.
FilmPart read_film_part(const std::string& path);
// The part an .exr already read holds (read_film_part without the reading). Trusts nothing:
// every number of the header is read strictly (digits only, no sign, nothing after it,
// within its range; sample ranges ascending, none past kSampleIndexLimit), the checksum
// must match where there is one, and the sample count pt:samples claims must agree with
// the film's own numbers: no pixel's sums may need more samples than it claims (by
// Cauchy-Schwarz, (sum of y)^2 <= N x (sum of y^2)), and the channel Y.variance must be
// what the sums give with that count. Else pt::Error(kExitBadScene) naming the file and the
// attribute. A part without pt:checksum is read (FilmPart::checksummed false), and the
// merge notes it.
FilmPart film_part_of(const ExrImage& image, const std::string& path);

// The note for a part read without a checksum (FilmPart::checksummed false), or "".
std::string unchecked_note(const FilmPart& part);

// Adds parts of one render up, in the order of their first samples. Throws
// pt::Error(kExitBadScene) naming the file and the field for a part of another render
// (stage, scene, options, seed, size), samples that two parts both hold, or a range past
// kSampleIndexLimit; `notes` gets a line for each gap in the samples, for parts of
// different backends and for each part without a checksum.
FilmPart merge_film_parts(std::vector<FilmPart> parts, std::vector<std::string>& notes);

}  // namespace pt
