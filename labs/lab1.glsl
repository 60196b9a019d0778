// Lab 1 (docs/labs/lab1.md): raycasting, the article's Eq. (2), Lout(p, w) = Lemitted(p, w).
// Write Li: the colour a camera ray sees. Built instead of stage1's Li when you
// configure with -DPT_LAB=1. Graded by `ctest -L lab1`.
// Written in the GLSL/C++ subset (docs/README.md): it runs on both backends.

#include "labs/lab_support.glsl"
#include "common/kernel/rng.glsl"
#include "common/kernel/camera.glsl"
#include "common/kernel/intersect.glsl"

// ray: the camera ray (ray.origin, ray.dir). Return, as the contract says:
//   - params.sky when the ray meets nothing (intersect_scene, kPrimNone);
//   - the emission of the surface hit if it emits and the ray sees its emitting side
//     (surface.front, or either side when material.double_sided != 0u);
//   - otherwise the surface's base colour ("every object emits", the article's assumption).
vec3 Li(Ray ray) {
  // Your code here. Remove the line below when you are done.
  return vec3(PT_LAB_NOT_WRITTEN(1, Li)) * ray.dir;
}
