// The command line of the contract (README.md), parsed with CLI11 (see options.h).
#include "common/app/options.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include <CLI/CLI.hpp>

#include "common/base/error.h"
#include "common/scene/scene_loading.h"
#include "common/kernel/scene_types.h"

namespace pt {

glm::vec3 parse_rgb(const std::string& text, const std::string& option) {
  std::istringstream in(text);
  glm::vec3 v;
  char comma1 = 0, comma2 = 0;
  in >> v.x >> comma1 >> v.y >> comma2 >> v.z;
  bool ok = !in.fail() && in.peek() == EOF && comma1 == ',' && comma2 == ',';
  for (int c = 0; c < 3 && ok; c++) ok = std::isfinite(v[c]) && v[c] >= 0.0f;
  if (!ok) {
    throw Error(kExitBadOption, option + " '" + text + "': expected three non-negative numbers R,G,B, e.g. " +
                                    option + " 0.5,0.5,0.5");
  }
  return v;
}

void parse_sample_range(const std::string& text, RenderSettings& settings) {
  const std::string usage = "; give --samples FIRST:COUNT, e.g. --samples 64:64 for the second 64 samples of each pixel";
  const std::size_t colon = text.find(':');
  auto number = [&](const std::string& part, const char* what) {
    if (part.empty() || part.find_first_not_of("0123456789") != std::string::npos || part.size() > 10) {
      throw Error(kExitBadOption, "--samples '" + text + "': " + what + " is not a whole number" + usage);
    }
    return std::stoull(part);
  };
  if (colon == std::string::npos) throw Error(kExitBadOption, "--samples '" + text + "' has no ':'" + usage);
  const std::uint64_t first = number(text.substr(0, colon), "FIRST");
  const std::uint64_t count = number(text.substr(colon + 1), "COUNT");
  if (count == 0) throw Error(kExitBadOption, "--samples '" + text + "': COUNT is 0, nothing to render" + usage);
  if (first + count > kSampleIndexLimit) {
    throw Error(kExitBadOption, "--samples '" + text + "' goes past sample index " + std::to_string(kSampleIndexLimit - 1) +
                                    ", the largest a render can address; use a smaller FIRST or COUNT");
  }
  settings.first_sample = first;
  settings.spp = count;
}

std::optional<Options> parse_options(int argc, char** argv, const StageInfo& stage) {
  Options o;
  o.render.spp = stage.default_spp;
  o.out = std::string("out/") + stage.name + ".png";
  std::string sky = "0,0,0";

  std::string footer = "\nBuilt-in scenes (--scene builtin:NAME):\n";
  for (const BuiltinInfo& b : builtin_scenes()) footer += "  " + b.name + std::string(17 - std::min<size_t>(16, b.name.size()), ' ') + b.description + "\n";
  CLI::App app(std::string(stage.name) + ": " + stage.summary, stage.name);
  app.footer(footer);
  app.get_formatter()->column_width(30);
  app.add_option("--scene", o.scene, "glTF 2.0 file (.gltf, .glb) or builtin:NAME")->capture_default_str();
  app.add_option("--width", o.render.width, "image width in pixels (given alone: a glTF camera's aspectRatio sets the height)")->capture_default_str()->check(CLI::Range(1, 65536));
  app.add_option("--height", o.render.height, "image height in pixels (given alone: a glTF camera's aspectRatio sets the width)")->capture_default_str()->check(CLI::Range(1, 65536));
  app.add_option("--spp", o.render.spp, "samples per pixel")->capture_default_str()->check(CLI::Range(std::uint64_t(1), std::uint64_t(0xffffffffu)));
  std::string samples;
  app.add_option("--samples", samples,
                 "render sample indices FIRST ... FIRST+COUNT-1 of every pixel (--spp N is 0:N); parts whose ranges "
                 "split at pass ends (1, 2, 4, 8, 16 and every multiple of 16) merge (pt_merge) into one run's "
                 "image bit for bit, other splits to float rounding")
      ->type_name("FIRST:COUNT");
  app.add_option("--seed", o.render.seed, "random seed: same seed, options and backend give the same image")->capture_default_str();
  app.add_option("--backend", o.backend,
                 "auto (gpu on a real GPU or on the device --device names, else cpu; says which on stderr), "
                 "cpu, or gpu (any Vulkan device, lavapipe too)")
      ->capture_default_str()->check(CLI::IsMember({"auto", "cpu", "gpu"}));
  app.add_option("--device", o.device, "Vulkan device: index or part of its name (env PT_VULKAN_DEVICE)");
  app.add_option("--camera", o.camera, "which of the glTF file's cameras: its index N or its (node's) name; default the first met");
  app.add_option("--gltf-scene", o.gltf_scene,
                 "which of the glTF file's scenes to draw: its index N or its name; default the file's `scene`")
      ->type_name("N|NAME");
  app.add_flag("--frame", o.frame,
               "frame the scene's bounds from a raised three-quarter view even where the file has a camera");
  app.add_option("--out", o.out, "output image: .exr (linear float), .png (8-bit sRGB) or .hdr")->capture_default_str();
  app.add_option("--sky", sky, "radiance R,G,B of rays that leave the scene")->capture_default_str();
  app.add_option("--env", o.env,
                 "equirectangular HDR environment map (.hdr or .exr) lighting the scene instead of --sky; "
                 "Blender's orientation for a world Environment Texture, +Y up")
      ->type_name("PATH");
  app.add_option("--env-strength", o.env_strength, "scales the environment map's radiance")->capture_default_str();
  app.add_option("--env-rotate", o.env_rotate,
                 "turns the environment map about the up axis by DEGREES (as Blender's Mapping node's Z rotation)")
      ->capture_default_str()->type_name("DEGREES");
  app.add_option("--exposure", o.exposure, "exposure in stops applied to .png output")->capture_default_str();
  app.add_option("--threads", o.threads, "CPU backend threads (0 = all cores)")
      ->capture_default_str()
      ->check(CLI::Range(0u, 1024u));
  app.add_option("--time-budget", o.render.time_budget,
                 "render in passes until SECONDS are spent (--spp, if given, still caps the samples)")
      ->check(CLI::Range(0.0, 1e9));
  app.add_option("--target-error", o.render.target_error,
                 "render in passes until the estimated per-pixel relative error (RMS over pixels of each pixel's "
                 "standard error, over the image's mean; checked from 16 spp) is below E")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--error-map", o.error_map,
                 "also write each pixel's estimated standard error over the image's mean: .png grey, black 0 to "
                 "white 2 x --target-error (else 2 x the printed per-pixel error); .exr/.hdr the values")
      ->type_name("PATH");
  app.add_flag("--keep-halves", o.keep_halves,
               "with an .exr --out under the default sampler: also keep the first half of the samples' luminance "
               "sums (channels film.Yhalf), from which pt_compare estimates the noise far better (docs/film.md); "
               "a merge of parts that do not split at the half cannot keep them");
  std::string sampler = "sobol";
  app.add_option("--sampler", sampler,
                 "where the random numbers come from: sobol (Owen-scrambled Sobol points, stratified) or "
                 "independent (independent uniform numbers); both unbiased")
      ->capture_default_str()->check(CLI::IsMember({"sobol", "independent"}));
  std::string accel = "bvh";
  app.add_option("--accel", accel, "triangle search: bvh (a bounding volume hierarchy) or none (every triangle); the same image")
      ->capture_default_str()->check(CLI::IsMember({"bvh", "none"}));
  app.add_flag("--all-features", o.render.all_features,
               "run the general kernel instead of the one specialised to the scene's features");
  app.add_option("--checkpoint", o.checkpoint,
                 "save the running render to <out>.ckpt (with --resume PATH: to PATH) every SECONDS (and at Ctrl-C); "
                 "removed when the render reaches --spp")
      ->check(CLI::Range(0.0, 1e9));
  app.add_option("--resume", o.resume_path,
                 "continue the checkpoint PATH (default <out>.ckpt) to --spp, saving to it again with --checkpoint; same "
                 "options as the saved render")
      ->expected(0, 1)
      ->type_name("[PATH]");
  std::string rr = stage.default_roulette == kRouletteThroughput ? "throughput" : "fixed";
  if (stage.has_roulette) {
    app.add_option("--rr", rr, std::string("Russian roulette: fixed (the article's p = 1/2) or throughput (") +
                                   stage.throughput_p + ")")
        ->capture_default_str()->check(CLI::IsMember({"fixed", "throughput"}));
    app.add_option("--depth-cap", o.render.depth_cap, "bounces after which a path is stopped and counted (a safety net)")
        ->capture_default_str()->check(CLI::Range(1u, 1000000u));
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::printf("%s", app.help().c_str());
    return std::nullopt;
  } catch (const CLI::ParseError& e) {
    std::string what = e.what();
    throw Error(kExitBadOption, what.substr(0, what.find('\n')) + "; run " + stage.name + " --help for the options");
  }
  o.render.sky = parse_rgb(sky, "--sky");
  if (app.count("--env") && o.env.empty()) {
    throw Error(kExitBadOption, "--env is empty: give the path of an .hdr or .exr environment map");
  }
  if (!o.env.empty() && o.render.sky != glm::vec3(0.0f)) {
    throw Error(kExitBadOption, "--env and --sky both light the scene from infinitely far: use one (the map replaces the uniform sky)");
  }
  for (const char* option : {"--env-strength", "--env-rotate"}) {
    if (o.env.empty() && app.count(option)) {
      throw Error(kExitBadOption, std::string(option) + " applies to an environment map: give --env PATH too");
    }
  }
  if (!std::isfinite(o.env_strength) || o.env_strength < 0.0f) {
    throw Error(kExitBadOption, "--env-strength must be a finite number >= 0 (1 keeps the map's own radiance)");
  }
  if (!std::isfinite(o.env_rotate)) throw Error(kExitBadOption, "--env-rotate must be a finite number of degrees");
  if (o.frame && !o.camera.empty())
    throw Error(kExitBadOption, "--frame and --camera both choose the view: use one");
  o.width_given = app.count("--width") > 0;
  o.height_given = app.count("--height") > 0;
  if (!samples.empty()) {
    if (app.count("--spp")) throw Error(kExitBadOption, "--spp and --samples both give the samples: use one (--spp N is --samples 0:N)");
    parse_sample_range(samples, o.render);
  }
  o.resume = app.count("--resume") > 0;
  if (o.resume && o.resume_path.empty()) o.resume_path = o.out + ".ckpt";
  // With a time or error target and no --spp, the samples are not capped.
  if ((o.render.time_budget > 0.0 || o.render.target_error > 0.0) && app.count("--spp") == 0 && samples.empty()) {
    o.render.spp = 0xffffffffu;
  }
  o.render.roulette = rr == "throughput" ? kRouletteThroughput : kRouletteFixed;
  o.render.accel = accel == "none" ? kAccelNone : kAccelBvh;
  o.render.sampler = sampler == "independent" ? kSamplerIndependent : kSamplerSobol;
  if (!std::isfinite(o.exposure)) throw Error(kExitBadOption, "--exposure must be a finite number of stops");
  // CLI::Range lets NaN through (every comparison with it is false), and NaN is no "off".
  for (auto [name, value] : {std::pair{"--checkpoint", o.checkpoint}, {"--time-budget", o.render.time_budget},
                             {"--target-error", o.render.target_error}}) {
    if (std::isnan(value)) {
      throw Error(kExitBadOption, std::string(name) + " is not a number (NaN); give a number, or leave the option out");
    }
  }
  return o;
}

}  // namespace pt
