// The steps of a stage's main() (app.h).
#include "common/app/app.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <new>

#include "common/app/checkpoint.h"
#include "common/app/error_map.h"
#include "common/app/replace_file.h"
#include "common/base/error.h"
#include "common/render/interrupt.h"
#include "common/render/memory.h"
#include "common/scene/environment.h"
#include "common/scene/scene_loading.h"
#include "common/scene/scene_sanity.h"

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

// The render as its memory sees it (common/render/memory.h); gpu: the backend that renders it.
FramePlan frame_plan(const Options& o, const Scene* scene, bool gpu) {
  return {o.render.width, o.render.height, o.resume, gpu, o.out, o.error_map, scene, o.render.accel == kAccelBvh,
          o.keep_halves, o.threads};
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

// The camera: --camera's choice, or the first met (saying so when there are others), or
// one that frames the bounds (saying so): where the file has none, or with --frame.
void choose_camera(Scene& scene, const Options& options, const char* stage) {
  if (options.frame) {
    scene.camera.reset();  // --frame: the bounds framed, whatever cameras the file has
  } else if (!options.camera.empty()) {
    select_camera(scene, options.camera);
  } else if (scene.cameras.size() > 1) {
    const SceneCamera& first = scene.cameras.front();
    std::fprintf(stderr, "%s: %s has %zu cameras; using the first met, %d '%s' (--camera N|NAME picks another)\n",
                 stage, scene.name.c_str(), scene.cameras.size(), first.index,
                 (first.name.empty() ? first.node : first.name).c_str());
  }
  if (!scene.camera) {
    CameraDesc framing = frame_bounds(scene.bounds(), float(options.render.width) / float(options.render.height));
    glm::vec3 eye(framing.to_world[3]);
    if (options.frame) {
      std::fprintf(stderr, "%s: --frame: framing the bounds of %s from a raised three-quarter view (eye at %.4g, %.4g, %.4g)\n",
                   stage, scene.name.c_str(), eye.x, eye.y, eye.z);
    } else {
      std::fprintf(stderr,
                   "%s: %s has no camera: framing its bounds from a raised three-quarter view (eye at %.4g, %.4g, "
                   "%.4g); add a camera to the file to choose the view\n",
                   stage, scene.name.c_str(), eye.x, eye.y, eye.z);
    }
  }
}

// A perspective camera's aspectRatio sizes the image when only one side is given; a size
// that disagrees with it is said once.
void apply_aspect_ratio(const Scene& scene, Options& options, const char* stage) {
  if (!scene.camera || scene.camera->kind != kCameraPerspective || !(scene.camera->aspect_ratio > 0.0f)) return;
  const double ratio = scene.camera->aspect_ratio;
  RenderSettings& r = options.render;
  auto side = [](double v) { return int(std::clamp(std::lround(v), 1L, 65536L)); };
  if (options.width_given != options.height_given) {
    if (options.width_given) r.height = side(r.width / ratio);
    else r.width = side(r.height * ratio);
    check_memory(frame_plan(options, nullptr, options.backend == "gpu"));
    std::fprintf(stderr, "%s: the camera's aspectRatio %.4g sets the image to %d x %d\n", stage, ratio, r.width,
                 r.height);
    return;
  }
  const double given = double(r.width) / double(r.height);
  if (std::abs(given / ratio - 1.0) <= 0.01) return;
  if (options.width_given) {
    std::fprintf(stderr,
                 "%s: the camera's aspectRatio %.4g differs from --width/--height (%.4g); the image is %d x %d with "
                 "the camera's vertical field of view\n",
                 stage, ratio, given, r.width, r.height);
  } else {
    std::fprintf(stderr, "%s: the camera's aspectRatio is %.4g; give --width alone to size the image by it (rendering %d x %d)\n",
                 stage, ratio, r.width, r.height);
  }
}

// What this stage can see of the scene's lights: delta lights only by light sampling, and
// with no light at all the image is black.
void warn_about_lights(const Scene& scene, const Options& options, const Stage& stage) {
  const char* name = stage.info.name;
  const bool sky = options.render.sky != glm::vec3(0.0f) || scene.environment;
  const bool area_lights = scene.lights.size() > scene.point_lights.size();
  if (!scene.point_lights.empty() && !stage.info.sees_point_lights) {
    std::fprintf(stderr,
                 "%s: the scene's %zu punctual light(s) (point, spot, directional) are delta lights: only light "
                 "sampling (stage4, stage5) sees them%s\n",
                 name, scene.point_lights.size(),
                 area_lights || sky || stage.info.every_surface_emits ? "" : ", so this image will be black");
  }
  if (!stage.info.every_surface_emits && !sky && !area_lights && scene.point_lights.empty()) {
    std::fprintf(stderr,
                 "%s: %s has no light (no emissive material, no KHR_lights_punctual light) and --sky is 0,0,0: the "
                 "image will be black; light it with --sky 1,1,1 (a uniform white sky), --env MAP.hdr, or give a material emission\n",
                 name, scene.name.c_str());
  }
}

}  // namespace

Scene load_stage_scene(Options& options, const Stage& stage) {
  set_scene_memory_budget(available_memory_bytes());  // the glTF loader's triangle budget (scene_sanity.h)
  Scene scene = load_scene(options.scene, options.gltf_scene);
  if (!options.env.empty()) {
    MemoryStep step("reading the environment map '" + options.env + "'");
    scene.environment = load_environment(options.env, options.env_strength, options.env_rotate);
  }
  choose_camera(scene, options, stage.info.name);
  apply_aspect_ratio(scene, options, stage.info.name);
  warn_about_lights(scene, options, stage);
  if (scene.environment && stage.info.sees_point_lights) {  // light sampling (stages 4, 5): say how it is picked
    std::fprintf(stderr, "%s: environment map %s (%u x %u, mean luminance %.4g): light sampling picks it with probability %.3g%s\n",
                 stage.info.name, scene.environment->path.c_str(), scene.environment->width, scene.environment->height,
                 scene.environment->mean_luminance, double(sky_pick_probability(scene, glm::vec3(0.0f))),
                 scene.lights.empty() ? " (the scene has no other light)" : ", the scene's other lights by their power");
  }
  return scene;
}

AutoBackendChoice auto_backend_choice(const std::vector<VulkanDevice>& devices) {
  using Type = VulkanDevice::Type;
  // The real GPU that VulkanContext takes without --device: discrete before integrated
  // before virtual, the first of its kind.
  const VulkanDevice* best = nullptr;
  for (Type type : {Type::discrete, Type::integrated, Type::virtual_gpu}) {
    for (const VulkanDevice& d : devices) {
      if (!best && d.type == type) best = &d;
    }
  }
  if (best) {
    const char* kind = best->type == Type::discrete ? "discrete" : best->type == Type::integrated ? "integrated" : "virtual";
    return {true, "GPU " + best->name + " (" + kind + ")"};
  }
  if (devices.empty()) return {false, "CPU (no Vulkan device found)"};
  auto what = [](const VulkanDevice& d) {
    return d.type == Type::cpu ? "emulates a GPU on the CPU" : "is no known kind of GPU";
  };
  if (devices.size() == 1) {
    return {false, "CPU (the only Vulkan device, " + devices[0].name + ", " + what(devices[0]) +
                       "; --backend gpu uses it)"};
  }
  std::string list;
  for (std::size_t i = 0; i < devices.size(); i++) {
    list += (i ? ", " : "") + std::to_string(i) + " " + devices[i].name + " " + what(devices[i]);
  }
  return {false, "CPU (no Vulkan device is a GPU: " + list + "; --backend gpu or --device N uses one)"};
}

std::unique_ptr<Backend> choose_backend(const Options& options, const Stage& stage) {
  const Backends& b = stage.backends;
  if (options.backend == "cpu") return b.cpu(stage.kernels, options.threads);
  if (options.backend == "gpu") return b.gpu(stage.kernels, options.device);
  // auto: a device named by --device or PT_VULKAN_DEVICE is used whatever its kind (lavapipe
  // too); without one, only a real GPU, since lavapipe is slower than the CPU backend.
  const char* name = stage.info.name;
  const char* env = std::getenv("PT_VULKAN_DEVICE");
  const std::string asked = !options.device.empty() ? "as --device " + options.device + " asks"
                            : env && *env          ? std::string("as PT_VULKAN_DEVICE=") + env + " asks"
                                                   : "";
  try {
    std::string why;
    if (asked.empty()) {
      AutoBackendChoice choice = b.gpu_devices ? auto_backend_choice(b.gpu_devices())
                                               : AutoBackendChoice{false, "CPU (this program has no GPU backend)"};
      if (!choice.gpu) {
        std::fprintf(stderr, "%s: --backend auto: %s\n", name, choice.why.c_str());
        return b.cpu(stage.kernels, options.threads);
      }
      why = choice.why;
    }
    std::unique_ptr<Backend> gpu = b.gpu(stage.kernels, options.device);
    if (why.empty()) why = "GPU " + gpu->device_name() + ", " + asked;
    std::fprintf(stderr, "%s: --backend auto: %s\n", name, why.c_str());
    return gpu;
  } catch (const Error& e) {
    if (e.code() != kExitNoDevice) throw;
    std::fprintf(stderr, "%s: %s; --backend auto falls back to the CPU\n", name, e.what());
    return b.cpu(stage.kernels, options.threads);
  }
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
