// --error-map PATH: a picture of the noise, for students to look at. Each pixel shows its
// estimated standard error (Film::pixel_standard_error) divided by the image's mean
// luminance, so the RMS of the map is the summary line's per-pixel relative error.
// .png: grey, black = 0 to white = the white level (error_map_white), linear in the 8-bit
// code; .exr and .hdr: the values themselves. Written atomically like the image.
#pragma once

#include <string>
#include <vector>

#include "common/app/image_output.h"
#include "common/render/film.h"

namespace pt {

// The map's file, checked before the render like --out's (exit 2 for an unknown type,
// 5 for a folder that cannot take it), with --error-map named in the message.
OutputFile error_map_file(const std::string& path);

// Per pixel, top row first: pixel_standard_error / mean_luminance (0 when unknown: below
// 2 spp or a black image).
std::vector<float> relative_error_values(const Film& film);

// The PNG's white: 2 x the target error when one is given, else 2 x the RMS of the values
// above (Film::sample_variance_relative_error: the average noise is then mid-grey), 1 when
// that is 0 or not finite. Under randomised QMC the values, like that RMS, are upper bounds
// of the pixels' errors (docs/sampling.md).
double error_map_white(const Film& film, double target_error);

// Writes the map of `film` to `file` (the image's metadata: stage, scene, spp, seed).
void write_error_map(const OutputFile& file, const Film& film, double target_error, const ImageMetadata& meta);

}  // namespace pt
