// The render as its memory sees it (common/render/memory.h, FramePlan), made from the
// options: what the steps of app.h check before anything large is made (the image's part
// before the scene, again when the camera's aspectRatio sizes the image, then with the scene).
// Not part of the article: the machinery of the stage programs.
#pragma once

#include "common/app/options.h"
#include "common/kernel/scene_types.h"
#include "common/render/memory.h"

namespace pt {

// gpu: whether the GPU backend renders it.
inline FramePlan frame_plan(const Options& o, const Scene* scene, bool gpu) {
  return {o.render.width, o.render.height, o.resume, gpu, o.out, o.error_map, scene, o.render.accel == kAccelBvh,
          o.keep_halves, o.threads};
}

}  // namespace pt
