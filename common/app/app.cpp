// The steps of a stage's main() (app.h).
#include "common/app/app.h"

#include <cstdio>
#include <filesystem>
#include <new>

#include "common/app/checkpoint.h"
#include "common/app/error_map.h"
#include "common/base/error.h"
#include "common/render/interrupt.h"
#include "common/render/memory.h"
#include "common/scene/scene_loading.h"

namespace pt {

int run_guarded(const char* stage, const std::function<int()>& body, int internal_error_code) {
  try {
    return body();
  } catch (const Error& e) {
    std::fprintf(stderr, "%s: %s\n", stage, e.what());
    return e.code();
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "%s: out of memory; render a smaller image or scene\n", stage);
    return kExitBadOption;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: internal error: %s; please report it with the command line\n", stage, e.what());
    return internal_error_code;
  }
}

std::optional<Options> read_options(int argc, char** argv, const Stage& stage) {
  std::optional<Options> options = parse_options(argc, argv, stage.info);
  if (!options) return options;
  install_interrupt_handlers();
  check_image_memory(options->render.width, options->render.height, options->resume);
  if (!options->error_map.empty()) error_map_file(options->error_map);  // exit 2 or 5 now, not after the render
  return options;
}

Scene load_stage_scene(const Options& options, const Stage& stage) {
  Scene scene = load_scene(options.scene);
  if (!scene.point_lights.empty() && !stage.info.sees_point_lights) {
    std::fprintf(stderr, "%s: the scene's %zu point light(s) are delta lights: only light sampling (stage4, stage5) sees them\n",
                 stage.info.name, scene.point_lights.size());
  }
  return scene;
}

std::unique_ptr<Backend> choose_backend(const Options& options, const Stage& stage) {
  const Backends& b = stage.backends;
  if (options.backend == "cpu") return b.cpu(stage.kernels, options.threads);
  if (options.backend == "gpu") return b.gpu(stage.kernels, options.device);
  try {
    return b.gpu(stage.kernels, options.device);
  } catch (const Error& e) {
    if (e.code() != kExitNoDevice) throw;
    std::fprintf(stderr, "%s: %s; --backend auto falls back to the CPU\n", stage.info.name, e.what());
    return b.cpu(stage.kernels, options.threads);
  }
}

namespace {

std::string checkpoint_path(const Options& options) { return options.out + ".ckpt"; }

// The image's metadata, and for an .exr what identifies the render (film_file.h): the
// scene's content hash is computed only for an .exr, which is the one that carries it.
ImageMetadata part_metadata(const char* stage, const Options& options, const Backend& backend, const Scene& scene,
                            const RenderResult& result) {
  ImageMetadata meta = image_metadata(stage, options, backend, result);
  if (OutputFile::is_exr(options.out)) meta.identity = film_identity(stage, scene, options.render);
  return meta;
}

// --resume: the saved state, checked against this render.
RenderResult resumed_state(const Options& options, const Stage& stage, std::uint64_t key) {
  const RenderSettings& s = options.render;
  RenderResult state = load_checkpoint(options.resume_path, key, stage.info.name, s.width, s.height, s.first_sample);
  if (state.film.spp() > s.spp) {
    throw Error(kExitBadOption, "checkpoint '" + options.resume_path + "' has " + std::to_string(state.film.spp()) +
                                    " spp, more than --spp " + std::to_string(s.spp) +
                                    "; ask for at least that many");
  }
  return state;
}

}  // namespace

RenderResult render_frame(std::unique_ptr<Backend>& backend, const Scene& scene, const Options& options,
                          const Stage& stage) {
  const char* name = stage.info.name;
  // The checkpoint's key hashes the whole scene (82 MB for a million triangles): only when
  // a checkpoint is written or read.
  const bool checkpoints = options.resume || options.checkpoint > 0.0;
  const std::uint64_t key = checkpoints ? render_key(name, scene, options.render) : 0;
  RenderHooks hooks;
  hooks.progress = true;
  hooks.label = name;
  std::optional<RenderResult> resumed;
  if (options.resume) hooks.resume = &resumed.emplace(resumed_state(options, stage, key));
  if (options.checkpoint > 0.0) {
    hooks.save_seconds = options.checkpoint;
    // A checkpoint that cannot be written (a full disk) must not end the render.
    hooks.save = [&, path = checkpoint_path(options)](const RenderResult& state) {
      try {
        save_checkpoint(path, key, name, state);
      } catch (const Error& e) {
        warn_once(std::string(e.what()) + "; the render goes on without checkpoints");
      }
    };
  }
  // The BVH once, before the first pass: a fallback to the CPU searches the same one.
  std::optional<Bvh> bvh;
  if (options.render.accel == kAccelBvh && !scene.triangles.empty()) hooks.bvh = &bvh.emplace(build_bvh(scene.triangles));
  RenderResult result = render(*backend, scene, options.render, hooks);
  if (!result.device_error.empty() && options.backend == "auto" && backend->kind() == "gpu") {
    // The device failed: never retried; the CPU goes on from the samples done.
    std::fprintf(stderr, "%s: %s; --backend auto falls back to the CPU and goes on from the %llu spp done\n", name,
                 result.device_error.c_str(), (unsigned long long)result.film.spp());
    backend = stage.backends.cpu(stage.kernels, options.threads);
    RenderResult so_far = std::move(result);
    hooks.resume = &so_far;
    result = render(*backend, scene, options.render, hooks);
  }
  if (bvh) result.seconds += bvh->stats.build_seconds;  // the time the user waited for
  return result;
}

int write_result(const OutputFile& out, const Options& options, const Backend& backend, const Scene& scene,
                 const RenderResult& result, const Stage& stage) {
  const char* name = stage.info.name;
  const std::uint64_t spp = result.film.spp();
  if (!result.device_error.empty()) {
    // --backend gpu: the samples done so far are written, then the device's error, exit 4.
    if (spp > 0) {
      out.write(result.film.mean_rgb(), options.render.width, options.render.height,
                part_metadata(name, options, backend, scene, result), options.exposure);
    }
    std::string done = spp > 0 ? "the " + std::to_string(spp) + " spp done are in " + options.out : "nothing was rendered";
    std::fprintf(stderr, "%s: %s; %s\n", name, result.device_error.c_str(), done.c_str());
    return int(kExitNoDevice);
  }
  // The image atomically, then the one summary line.
  out.write(result.film.mean_rgb(), options.render.width, options.render.height,
            part_metadata(name, options, backend, scene, result), options.exposure);
  if (!options.error_map.empty()) {
    write_error_map(error_map_file(options.error_map), result.film, options.render.target_error,
                    image_metadata(name, options, backend, result));
  }
  // A finished render needs its checkpoint no more.
  if (spp >= options.render.spp && (options.checkpoint > 0.0 || options.resume)) {
    std::error_code ignored;
    const std::string checkpoint = checkpoint_path(options);
    if (std::filesystem::is_regular_file(checkpoint, ignored)) std::filesystem::remove(checkpoint, ignored);
  }
  std::string tags = "[scene: " + scene_features(scene, options.render.sky) + "]";
  if (options.render.all_features) tags += " [kernel: general, --all-features]";
  std::printf("%s\n", summary_line(name, backend, result, tags).c_str());
  if (int signo = interrupt_signal()) {
    std::fprintf(stderr, "%s: interrupted after %llu of the samples per pixel asked for; the image has them\n", name,
                 (unsigned long long)spp);
    return 128 + signo;
  }
  return 0;
}

}  // namespace pt
