// The sRGB transfer function (IEC 61966-2-1): an sRGB-encoded value as linear light, in
// double on the host. common/kernel/texture_lookup.glsl decodes texels with the same curve
// in the kernel; the light table's texture means (common/scene/scene_lights.cpp), the grey levels
// of the error map and of pt_compare's picture (common/app/), and the tests' expected
// texel values use this one.
#pragma once

#include <cmath>

namespace pt {

// c in [0, 1], encoded: the linear value.
inline double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

}  // namespace pt
