// The environment map on the host (issue #49; beyond the article, whose sky is one colour):
// an equirectangular HDR image (--env, .hdr or .exr read with OpenImageIO) scaled by
// --env-strength, and the tables of the 2D distribution that stages 4 and 5 sample it by
// (common/kernel/environment.glsl reads both). docs/environment.md shows the orientation.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "common/kernel/scene_types.h"

namespace pt {

struct Environment {
  std::string path;           // the file (or a test's name for a map it made)
  uint width = 0, height = 0;  // texels
  float strength = 1.0f;       // --env-strength, already in `radiance`
  float rotate_degrees = 0.0f; // --env-rotate: the turn about +Y (FrameParams env_cos, env_sin)
  // RGB radiance per texel (x strength), rows from the image's top: 3 x width x height.
  std::vector<float> radiance;
  // environment.glsl's environment_table: the texels' pdf over the unit square of (u, v),
  // the rows' cumulative distribution (height + 1), each row's over its columns (width + 1).
  std::vector<float> table;
  // The luminance averaged over the sphere of directions (the integral of L over 4 pi):
  // what a uniform sky of the same power would have (light picking, sky_pick_probability).
  double mean_luminance = 0.0;
};

// An environment from RGB radiance (3 x width x height floats, rows from the top): scales by
// strength and builds the distribution. Throws pt::Error(kExitBadScene) where a texel is not
// finite; negative values are taken as 0 (say so on stderr, once).
std::shared_ptr<const Environment> make_environment(std::string name, uint width, uint height,
                                                    std::vector<float> rgb, float strength, float rotate_degrees);

// --env PATH: reads an equirectangular .hdr or .exr (its first three channels; one channel is
// grey); strength and rotate_degrees as parse_options checked them (finite, strength >= 0).
// Throws pt::Error: kExitBadOption for another extension, kExitBadScene for a file that
// cannot be read or holds no usable image.
std::shared_ptr<const Environment> load_environment(const std::string& path, float strength, float rotate_degrees);

// The map's turn about +Y (rotate_degrees) as (cos, sin): FrameParams env_cos, env_sin.
glm::vec2 environment_turn(const Environment& env);

// The pdf table's value for texel (x, y): proportional to the map's luminance averaged over
// the texel (as the bilinear lookup spreads it) times the solid angle of its row.
// Exposed for the tests of environment.glsl.
std::vector<float> environment_weights(const std::vector<float>& rgb, uint width, uint height);

}  // namespace pt
