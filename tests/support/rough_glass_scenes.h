// Scenes of the rough glass tests (issue #46, KHR_materials_transmission with roughness;
// tests/stages/test_rough_glass_images.cpp, tests/gpu/test_cpu_gpu_agree.cpp): builtin
// glass_slab's slab and emitter with the slab made rough, and a rough glass sphere alone
// under the sky (a furnace).
#pragma once

#include "common/scene/analytic_scenes.h"
#include "common/scene/scene.h"

namespace pt::test {

// The glass slab of builtin:glass_slab (ior 1.5 between an orthographic camera and a
// uniform emitter behind it, which the camera sees only through the slab), rough.
inline Scene rough_glass_slab(float roughness) {
  Scene s = analytic::make_glass_slab({});
  s.materials.at(0) = make_rough_glass(glm::vec3(1.0f), 1.5f, roughness);
  return s;
}

// A white rough glass sphere of radius 1 filling most of a perspective view; render it
// with a sky.
inline Scene rough_glass_sphere(float roughness) {
  Scene s = analytic::make_sphere({});
  s.materials.at(0) = make_rough_glass(glm::vec3(1.0f), 1.5f, roughness);
  return s;
}

}  // namespace pt::test
