// The pieces of a stage's main() (see app.h).
#include "common/app/app.h"

#include <cstdio>
#include <filesystem>
#include <new>
#include <optional>

#include "common/app/checkpoint.h"
#include "common/base/error.h"
#include "common/render/interrupt.h"
#include "common/scene/scene_loading.h"

namespace pt {

int guarded_main(const char* stage, const std::function<int()>& body) {
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
    return 1;
  }
}

int run_stage(int argc, char** argv, const StageInfo& stage, const StageKernels& kernels,
              GpuBackendFactory make_gpu) {
  return guarded_main(stage.name, [&] {
    // Parse: the options of the contract (README.md).
    std::optional<Options> options = parse_options(argc, argv, stage);
    if (!options) return 0;  // --help
    install_interrupt_handlers();
    OutputFile out(options->out);  // checked now, written after the render
    check_image_memory(options->width, options->height, options->resume);
    // Load: a glTF file or a built-in scene.
    Scene scene = load_scene(options->scene);
    if (!scene.point_lights.empty() && !stage.sees_point_lights) {
      std::fprintf(stderr, "%s: the scene's %zu point light(s) are delta lights: only light sampling (stage4) sees them\n",
                   stage.name, scene.point_lights.size());
    }
    // Render: passes on the CPU or the GPU, from a checkpoint if asked, saving one if asked.
    RenderSettings settings = render_settings(*options, stage.name);
    const std::uint64_t key = render_key(stage.name, scene, settings);
    const std::string checkpoint = options->out + ".ckpt";
    std::optional<RenderResult> resumed;
    if (options->resume) {
      resumed = load_checkpoint(options->resume_path, key, stage.name, options->width, options->height);
      if (resumed->film.spp() > settings.spp) {
        throw Error(kExitBadOption, "checkpoint '" + options->resume_path + "' has " +
                                        std::to_string(resumed->film.spp()) + " spp, more than --spp " +
                                        std::to_string(settings.spp) + "; ask for at least that many");
      }
      settings.resume = &*resumed;
    }
    if (options->checkpoint > 0.0) {
      settings.save_seconds = options->checkpoint;
      // A checkpoint that cannot be written (a full disk) must not end the render.
      settings.save = [&](const RenderResult& state) {
        try {
          save_checkpoint(checkpoint, key, stage.name, state);
        } catch (const Error& e) {
          warn_once(std::string(e.what()) + "; the render goes on without checkpoints");
        }
      };
    }
    std::unique_ptr<Backend> backend = make_backend(*options, kernels, make_gpu);
    RenderResult result = render(*backend, scene, settings);
    if (!result.device_error.empty() && options->backend == "auto" && backend->kind() == "gpu") {
      // The device failed: never retried; the CPU goes on from the samples done.
      std::fprintf(stderr, "%s: %s; --backend auto falls back to the CPU and goes on from the %llu spp done\n",
                   stage.name, result.device_error.c_str(), (unsigned long long)result.film.spp());
      backend = make_cpu_backend(kernels, options->threads);
      RenderResult so_far = std::move(result);
      settings.resume = &so_far;
      result = render(*backend, scene, settings);
    }
    if (!result.device_error.empty()) {
      // --backend gpu: the samples done so far are written, then the device's error, exit 4.
      if (result.film.spp() > 0) {
        out.write(result.film.mean_rgb(), options->width, options->height,
                  image_metadata(stage.name, *options, *backend, result), options->exposure);
      }
      std::fprintf(stderr, "%s: %s; %s\n", stage.name, result.device_error.c_str(),
                   result.film.spp() > 0 ? ("the " + std::to_string(result.film.spp()) + " spp done are in " +
                                            options->out).c_str()
                                         : "nothing was rendered");
      return int(kExitNoDevice);
    }
    // Write: the image atomically, then the one summary line.
    out.write(result.film.mean_rgb(), options->width, options->height,
              image_metadata(stage.name, *options, *backend, result), options->exposure);
    // A finished render needs its checkpoint no more.
    if (result.film.spp() >= settings.spp && (options->checkpoint > 0.0 || options->resume)) {
      std::error_code ignored;
      if (std::filesystem::is_regular_file(checkpoint, ignored)) std::filesystem::remove(checkpoint, ignored);
    }
    std::string tags = "[scene: " + scene_features(scene, options->sky) + "]";
    if (options->all_features) tags += " [kernel: general, --all-features]";
    std::printf("%s\n", summary_line(stage.name, *backend, result, tags).c_str());
    if (int signo = interrupt_signal()) {
      std::fprintf(stderr, "%s: interrupted after %llu of the samples per pixel asked for; the image has them\n",
                   stage.name, (unsigned long long)result.film.spp());
      return 128 + signo;
    }
    return 0;
  });
}

std::unique_ptr<Backend> make_backend(const Options& options, const StageKernels& kernels,
                                      GpuBackendFactory make_gpu) {
  if (options.backend == "cpu") return make_cpu_backend(kernels, options.threads);
  if (options.backend == "gpu") return make_gpu(kernels, options.device);
  try {
    return make_gpu(kernels, options.device);
  } catch (const Error& e) {
    if (e.code() != kExitNoDevice) throw;
    std::fprintf(stderr, "%s: %s; --backend auto falls back to the CPU\n", kernels.name, e.what());
    return make_cpu_backend(kernels, options.threads);
  }
}

RenderSettings render_settings(const Options& o, const char* stage) {
  RenderSettings s;
  s.width = o.width;
  s.height = o.height;
  s.spp = o.spp;
  s.seed = o.seed;
  s.sky = o.sky;
  s.roulette = o.roulette;
  s.time_budget = o.time_budget;
  s.all_features = o.all_features;
  s.target_error = o.target_error;
  s.depth_cap = o.depth_cap;
  s.progress = true;
  s.label = stage;
  return s;
}

ImageMetadata image_metadata(const char* stage, const Options& o, const Backend& backend,
                             const RenderResult& r) {
  ImageMetadata m;
  m.stage = stage;
  m.backend = backend.kind() + " (" + backend.device_name() + ")";
  m.scene = o.scene;
  m.spp = r.film.spp();
  m.seed = o.seed;
  m.seconds = r.seconds;
  return m;
}

std::string summary_line(const char* stage, const Backend& backend, const RenderResult& r,
                         const std::string& tags) {
  const Film& f = r.film;
  double samples = double(f.width()) * double(f.height()) * double(f.spp());
  char line[512];
  std::snprintf(line, sizeof line, "%s: backend %s (%s), %dx%d, %llu spp, %.3f s, %.3g samples/s", stage,
                backend.kind().c_str(), backend.device_name().c_str(), f.width(), f.height(),
                (unsigned long long)f.spp(), r.seconds, r.seconds > 0.0 ? samples / r.seconds : 0.0);
  std::string s = line;
  if (f.spp() >= 2) {
    std::snprintf(line, sizeof line, ", estimated relative error %.2g", f.relative_standard_error());
    s += line;
  }
  // Events that are rare and deserve a word: each is said once, with its count.
  const RenderCounters& c = r.counters;
  if (c.non_finite) {
    std::uint32_t p = c.first_non_finite_pixel;
    s += ", " + std::to_string(c.non_finite) + " NaN/Inf samples dropped (first at pixel " +
         std::to_string(p % std::uint32_t(f.width())) + "," + std::to_string(p / std::uint32_t(f.width())) + ")";
  }
  if (c.zero_pdf) s += ", " + std::to_string(c.zero_pdf) + " paths ended by a zero pdf";
  if (c.depth_cap) s += ", " + std::to_string(c.depth_cap) + " paths stopped at the depth cap";
  if (c.loop_limit) {
    s += ", WRONG IMAGE: the Vulkan driver cut the loops of " + std::to_string(c.loop_limit) +
         " pixel passes short (lavapipe stops a kernel after 65535 loop iterations; fewer triangles, "
         "a lower albedo or --backend cpu)";
  }
  if (!tags.empty()) s += " " + tags;
  return s;
}

}  // namespace pt
