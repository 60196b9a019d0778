// The lab check build's stage1 integrator (cmake/Labs.cmake, PT_LAB_CHECK): Li is the
// student's from labs/lab1.glsl when PT_LAB_STUB=1 selects lab 1 at run time, else stage1's
// own. C++ only; included inside the kernel's namespace in place of the integrator.
#include "common/kernel/rng.glsl"  // what both versions use, outside the namespaces below
#include "common/kernel/intersect.glsl"
#include "common/kernel/texture.glsl"
#include "common/kernel/environment.glsl"  // the sky: --sky's colour or the map

namespace reference {
#include "stage1_raycast/integrator.glsl"
}  // namespace reference

namespace student {
#include "labs/lab1.glsl"
}  // namespace student

vec3 Li(Ray ray) {
  return pt::lab::selected() == 1 ? student::Li(ray) : reference::Li(ray);
}
