// --error-map PATH: a picture of the noise, for students to look at. Each pixel shows its
// estimated standard error divided by the image's mean luminance, from the estimate the
// summary line printed (Film::per_pixel_error_from_halves): its sample variance
// (Film::pixel_standard_error), or under the default sampler, where the two halves of the
// samples gave the smaller figure, their difference (Film::halves_variance) shared over
// each pixel's 3 x 3 window. Either way the RMS of the map is the summary line's per-pixel
// relative error.
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

// Per pixel, top row first: its estimated standard error (as the header says) over the
// image's mean luminance (0 when unknown: below 2 spp or a black image).
std::vector<float> relative_error_values(const Film& film);

// The PNG's white: 2 x the target error when one is given, else 2 x the printed per-pixel
// error (Film::per_pixel_relative_error, the RMS of the values above: the average noise is
// then mid-grey), 1 when that is 0 or not finite.
double error_map_white(const Film& film, double target_error);

// Writes the map of `film` to `file` (the image's metadata: stage, scene, spp, seed).
void write_error_map(const OutputFile& file, const Film& film, double target_error, const ImageMetadata& meta);

}  // namespace pt
