// load_stage_scene, the step of a stage's main() that loads --scene (app.h): the scene and
// its environment map, the camera chosen (or one that frames the bounds), the image's size
// completed by the camera's aspectRatio, and a word about lights this stage cannot see.
// Not part of the article: the machinery of the stage programs.
#include "common/app/app.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/app/frame_plan.h"
#include "common/render/memory.h"
#include "common/scene/environment.h"
#include "common/scene/scene_loading.h"
#include "common/scene/scene_sanity.h"

namespace pt {

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
                 "sampling (stages 4 to 6) sees them%s\n",
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

}  // namespace pt
