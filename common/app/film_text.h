// The film file's header as text (film_file.h), shared by the files that write, read and
// merge parts: how an error line names a part and quotes what it holds, and how whole numbers
// and sample ranges are read strictly. Not in the article: the machinery of parts and merges.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "common/app/film_file.h"

namespace pt::film_text {

// Throws pt::Error(kExitBadScene): "'PATH' WHY".
[[noreturn]] void refuse(const std::string& path, const std::string& why);

// A text from a file as an error line may show it: quoted, printable ASCII, at most `limit`
// characters (a header may hold anything, newlines too).
std::string shown(const std::string& text, std::size_t limit = 40);

// A whole number as format_ranges and std::to_string write it: digits only, no sign, no
// leading zero, nothing after it, at most `max` (checked before it could overflow).
bool parse_whole(const std::string& text, std::uint64_t max, std::uint64_t& value);

// A range a render can hold: not empty, and its end (first + count) at most kSampleIndexLimit,
// so that no end and no sum of one part's counts overflows.
bool addressable(const SampleRange& r);

// "FIRST:COUNT".
std::string range_text(const SampleRange& r);

}  // namespace pt::film_text
