// The steps of a stage's main() (app.h): the guard around them, the options, the render and
// the written result. Loading the scene is in app_scene.cpp, choosing the backend in
// app_backend.cpp.
#include "common/app/app.h"

#include <cstdio>
#include <filesystem>
#include <new>

#include "common/app/checkpoint.h"
#include "common/app/error_map.h"
#include "common/app/frame_plan.h"
#include "common/app/replace_file.h"
#include "common/base/error.h"
#include "common/render/interrupt.h"
#include "common/render/memory.h"

namespace pt {

int run_guarded(const char* stage, const std::function<int()>& body, int internal_error_code) {
  try {
    return body();
  } catch (const Error& e) {
    std::fprintf(stderr, "%s: %s\n", stage, e.what());
    return e.code();
  } catch (const std::bad_alloc&) {  // past the estimate (common/render/memory.h): say where
    const std::string step = MemoryStep::current();
    std::fprintf(stderr, "%s: out of memory%s; render a smaller image or scene, or give it more memory\n", stage,
                 step.empty() ? "" : (" while " + step).c_str());
    return kExitBadOption;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: internal error: %s; please report it with the command line\n", stage, e.what());
    return internal_error_code;
  }
}

namespace {

// Where --checkpoint saves: the checkpoint --resume continues, else <out>.ckpt.
std::string checkpoint_path(const Options& options) { return options.resume ? options.resume_path : options.out + ".ckpt"; }

void refuse_shared_outputs(const Options& options) {
  // Files a run writes or reads, each under the option that names it: no two may be one file.
  std::vector<std::pair<std::string, std::string>> files = {{"--out", options.out}};
  if (!options.error_map.empty()) files.emplace_back("--error-map", options.error_map);
  if (options.resume) files.emplace_back("--resume", options.resume_path);
  for (std::size_t i = 0; i < files.size(); i++) {
    for (std::size_t j = i + 1; j < files.size(); j++) {
      if (same_file(files[i].second, files[j].second)) {
        throw Error(kExitBadOption, files[j].first + " '" + files[j].second + "' is the same file as " +
                                        files[i].first + " '" + files[i].second + "'; give each its own name");
      }
    }
  }
}

}  // namespace

std::optional<Options> read_options(int argc, char** argv, const Stage& stage) {
  StageInfo info = stage.info;
  std::optional<Options> options = parse_options(argc, argv, info);
  if (!options) return options;
  install_interrupt_handlers();
  check_memory(frame_plan(*options, nullptr, options->backend == "gpu"));  // the image's part, before the scene
  refuse_shared_outputs(*options);
  if (!options->error_map.empty()) error_map_file(options->error_map);  // exit 2 or 5 now, not after the render
  return options;
}

namespace {

// The image's metadata, and for an .exr what identifies the render (film_file.h): the
// scene's content hash is computed only for an .exr, which is the one that carries it.
ImageMetadata part_metadata(const char* stage, const Options& options, const Backend& backend, const Scene& scene,
                            const RenderResult& result) {
  ImageMetadata meta = image_metadata(stage, options, backend, result);
  if (OutputFile::is_exr(options.out)) meta.identity = film_identity(stage, scene, options.render);
  meta.keep_halves = options.keep_halves;
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

// What the render needs, checked before anything large is made (common/render/memory.h):
// the device's limits (bvh: nullptr before the BVH is built), then the host's memory. Under
// --backend auto a device that cannot hold the render gives way to the CPU.
void check_frame_memory(std::unique_ptr<Backend>& backend, const Scene& scene, const Options& options,
                        const Stage& stage, const Bvh* bvh) {
  const RenderSettings& s = options.render;
  if (const auto* device = dynamic_cast<const DeviceMemoryLimits*>(backend.get())) {
    try {
      device->check_device_memory(scene, s.all_features ? kFeatureAll : scene_feature_mask(scene, s.sky),
                                  std::uint64_t(s.width) * std::uint64_t(s.height), bvh);
    } catch (const Error& e) {
      if (e.code() != kExitNoDevice || options.backend != "auto") throw;
      std::fprintf(stderr, "%s: %s; --backend auto falls back to the CPU\n", stage.info.name, e.what());
      backend = stage.backends.cpu(stage.kernels, options.threads);
    }
  }
  if (!bvh) check_memory(frame_plan(options, &scene, backend->kind() == "gpu"));
}

}  // namespace

RenderResult render_frame(std::unique_ptr<Backend>& backend, const Scene& scene, const Options& options,
                          const Stage& stage) {
  const char* name = stage.info.name;
  check_frame_memory(backend, scene, options, stage, nullptr);
  // The checkpoint's key hashes the whole scene (82 MB for a million triangles): only when
  // a checkpoint is written or read.
  const bool checkpoints = options.resume || options.checkpoint > 0.0;
  const std::uint64_t key = checkpoints ? render_key(name, scene, options.render) : 0;
  RenderHooks hooks;
  hooks.progress = true;
  hooks.label = name;
  std::optional<RenderResult> resumed;
  if (options.resume) {
    MemoryStep step("reading the checkpoint '" + options.resume_path + "'");
    hooks.resume = &resumed.emplace(resumed_state(options, stage, key));
  }
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
  if (options.render.accel == kAccelBvh && !scene.triangles.empty()) {
    MemoryStep step("building the BVH");
    hooks.bvh = &bvh.emplace(build_bvh(scene.triangles));
    check_frame_memory(backend, scene, options, stage, hooks.bvh);
  }
  MemoryStep step("rendering");
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
  MemoryStep step("writing the image '" + options.out + "'");
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
    MemoryStep map_step("writing the error map '" + options.error_map + "'");
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
