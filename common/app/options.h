// The command line every stage takes (the contract (README.md), "Programs"), parsed with CLI11.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "common/render/render.h"

namespace pt {

// What differs between the stages' command lines.
struct StageInfo {
  const char* name;         // "stage1_raycast"
  const char* summary;      // one line: the stage and its equation
  std::uint64_t default_spp;
  bool has_roulette = false;        // paths end by Russian roulette (stage2 onwards): --rr
  std::uint32_t default_roulette = 0;  // kRouletteFixed (the article) or kRouletteThroughput
  const char* throughput_p = "p = path weight";  // --rr's help: what the throughput roulette's p is
  bool sees_point_lights = false;   // light sampling (stage4) sees delta lights
  bool every_surface_emits = false; // stage1: surfaces show their base colour, so no scene is black
};

struct Options {
  std::string scene = "builtin:cornell";  // glTF path or builtin:NAME
  RenderSettings render;                  // size, spp, seed, sky, roulette, stopping rules
  std::string backend = "auto";           // auto, cpu or gpu
  std::string device;                     // GPU choice: index or part of the name (or PT_VULKAN_DEVICE)
  std::string out;                        // default out/<stage>.png
  float exposure = 0.0f;                  // stops, for .png output
  unsigned threads = 0;                   // CPU threads, 0 = all cores
  double checkpoint = 0.0;                // --checkpoint SECONDS: save <out>.ckpt this often (0: never)
  bool resume = false;                    // --resume [PATH]: continue a checkpoint
  std::string resume_path;                // its path (default <out>.ckpt)
  std::string error_map;                  // --error-map PATH: each pixel's relative error (error_map.h)
  bool keep_halves = false;               // --keep-halves: the .exr keeps the halves' sums (film_file.h)
  std::string camera;                     // --camera N|NAME: which of the file's cameras ("" = the first met)
  std::string gltf_scene;                 // --gltf-scene N|NAME: which of the file's scenes ("" = its default)
  std::string env;                        // --env PATH: an HDR environment map ("" = none: --sky)
  float env_strength = 1.0f;              // --env-strength S: scales its radiance
  float env_rotate = 0.0f;                // --env-rotate DEGREES: its turn about +Y (environment.glsl)
  bool frame = false;                     // --frame: frame the scene's bounds even where the file has a camera
  bool width_given = false;               // --width / --height were on the command line (a camera's
  bool height_given = false;              // aspectRatio sets the height when only the width is)
};

// Parses argv; prints the help and returns nothing for --help; throws pt::Error(2) with
// one line for anything wrong.
std::optional<Options> parse_options(int argc, char** argv, const StageInfo& stage);

// Parses --samples "FIRST:COUNT" into settings.first_sample and settings.spp, or throws
// pt::Error(2) with one line.
void parse_sample_range(const std::string& text, RenderSettings& settings);

// Parses "R,G,B" into three finite, non-negative numbers, or throws pt::Error(2).
glm::vec3 parse_rgb(const std::string& text, const std::string& option);

}  // namespace pt
