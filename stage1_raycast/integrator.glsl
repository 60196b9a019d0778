// stage1_raycast: the article's simplest algorithm, raycasting (section "Простейший
// алгоритм по методу бросания лучей", Eq. 2): Lout = Le. One ray per sample; the surface
// it meets shows its emission where it emits, otherwise its base colour, as if every
// object emitted its own colour (the article's assumption; the contract (README.md) "stage1").
// Written in the GLSL/C++ subset of cpu/kernel_prelude.h: both backends run it.
#include "common/kernel/rng.glsl"
#include "common/kernel/camera.glsl"
#include "common/kernel/intersect.glsl"
#include "common/kernel/texture.glsl"
#include "common/kernel/environment.glsl"

// Eq. (2): the radiance leaving the first surface towards the camera is its own.
vec3 Li(Ray ray) {
  Hit hit = intersect_scene(ray, kInfinity);
  if (hit.kind == kPrimNone) return sky_radiance(ray.dir);  // --sky, or the environment map
  Surface surface = surface_at(ray, hit);
  Material material = surface_material(surface);
  // Le: an emitter shines from its front face, or from both when double-sided.
  bool emits = max(material.emission.x, max(material.emission.y, material.emission.z)) > 0.0f;
  if (emits && (surface.front || material.double_sided != 0u)) return material.emission;
  // The article's assumption: every other object "emits" its base colour.
  return material.base_color;
}
