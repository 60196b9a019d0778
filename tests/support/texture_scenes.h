// Helpers of the texture image tests (issue #19; tests/stages/test_texture_images.cpp,
// test_texture_plane.cpp, test_texture_emissive_alpha.cpp), run by both executables: a
// texel decoded from sRGB, the path-tracing stages, and the sky plane under a uniform sky.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "common/base/srgb.h"
#include "common/scene/scene_loading.h"
#include "stage2_montecarlo/kernels.h"
#include "stage3_importance/kernels.h"
#include "stage4_direct_indirect/kernels.h"
#include "stage5_mis/kernels.h"
#include "tests/support/test_render.h"

namespace pt::test {

// A texel's colour decoded from sRGB, in double.
inline glm::dvec3 srgb_texel(uint v) {
  return glm::dvec3(pt::srgb_to_linear((v & 255u) / 255.0), pt::srgb_to_linear((v >> 8 & 255u) / 255.0),
                    pt::srgb_to_linear((v >> 16 & 255u) / 255.0));
}

inline std::vector<StageKernels> path_tracing_stages() {
  return {stage2::kernels(), stage3::kernels(), stage4::kernels(), stage5::kernels()};
}

// The sky plane (tests/data/gltf/tex_sky_plane.gltf): a 2 x 2 quad filling an orthographic
// view, its 4 x 4 texture repeated twice over it (u = x + 1, v = 1 - y), nearest texels.
const glm::dvec3 kSky(0.5, 1.0, 2.0);
// Stages 3 to 5 sample the plane's one bounce by its cosine: every sample is the pixel's
// value up to float rounding (the film's variance is about 0), so the image means are
// compared with that rounding allowed (channel_means_ratio's relative floor).
const double kRounding = 1e-5;

// A render's settings under the uniform sky kSky.
inline RenderSettings settings_under_sky(int width, int height, std::uint64_t spp, std::uint32_t seed) {
  RenderSettings s = settings(width, height, spp, seed);
  s.sky = glm::vec3(kSky);
  return s;
}

inline Scene sky_plane() {
  return load_gltf(PT_SOURCE_DIR "/tests/data/gltf/tex_sky_plane.gltf");
}

}  // namespace pt::test
