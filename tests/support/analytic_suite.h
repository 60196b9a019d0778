// The analytic images every path-tracing stage (2 to 5) must reproduce: the same scenes
// and expected values for each stage's kernel, on the backend under test. Each function
// CHECKs its scene against the closed form with variance-derived tolerances.
#pragma once

#include <cstdint>

#include "common/scene/analytic_scenes.h"
#include "common/render/backend.h"
#include "common/render/render.h"
#include "tests/support/image_checks.h"

namespace pt::test {

// Renders 8 independent batches, then: every pixel (check_pixels) and every channel's
// image mean (channel_means_ratio) against the expected image.
// relative_floor: see channel_means_ratio (image_checks.h).
void check_scene(const StageKernels& kernels, const Scene& scene, const ExpectedImage& expected, RenderSettings s,
                 double relative_floor = 0.0);

// Furnace box of the given albedo, emission 1: every pixel Le / (1 - albedo).
void check_furnace(const StageKernels& kernels, float albedo, std::uint32_t roulette, std::uint32_t seed);
// The spherical furnace of the given albedo, emission 1: every pixel Le / (1 - albedo).
void check_furnace_sphere(const StageKernels& kernels, float albedo, std::uint32_t seed);
// The furnace box with one bounce only (depth cap 1), albedo 0.5 and 0.8, emission 1: every
// pixel Le (1 + albedo), the camera hit's emission and its direct light, neither lost nor
// doubled (stages 4 to 6, whose direct light comes from light samples).
void check_one_bounce_furnace(const StageKernels& kernels, std::uint32_t seed);
// A diffuse sphere under a uniform sky: albedo x sky on it, the sky elsewhere.
void check_sky_sphere(const StageKernels& kernels, std::uint32_t seed);
// The closed-form image of the floor under the square (or triangle) light at size x size.
ExpectedImage floor_light_image(const analytic::FloorLightScene& scene, int size);
// A diffuse floor under a square light: Lambert's polygon formula, pixel by pixel.
void check_floor_light(const StageKernels& kernels, std::uint32_t seed, bool triangle = false);
// The floor under a one-sided square (or triangle) light turned away from it, facing up: a
// light sample must not light a point behind the emitter, so every pixel is exactly 0.
void check_light_turned_away(const StageKernels& kernels, std::uint32_t seed, bool triangle = false);
// A mirror reflecting an emitter straight back: F0 x Le.
void check_mirror(const StageKernels& kernels, std::uint32_t seed);
// A glass slab before an emitter: Le (1 - R) / (1 + R); invisible at ior 1.
void check_glass_slab(const StageKernels& kernels, float ior, std::uint32_t seed);
// A punctual light above a diffuse floor (light sampling only: stages 4 and 5), size x size
// pixels, averaged over each pixel: a point light (kPunctualPoint) albedo I cos / (pi d^2),
// a spot light pointing down that times its falloff, a directional light albedo E cos / pi.
void check_point_floor(const StageKernels& kernels, int size, std::uint32_t seed, uint kind = kPunctualPoint);
// Inside a diffuse sphere with a point light at its centre (stages 4 and 5): every pixel
// albedo I / (pi r^2) / (1 - albedo).
void check_point_in_sphere(const StageKernels& kernels, std::uint32_t seed);
// `test` and `reference` agree on the Cornell box (32 x 32, 64 spp, 16 batches each), over
// the image and in 4 x 4 regions (the boxes' soft shadows among them), each channel:
// Welch t-tests over the batches, Sidak-corrected over all of them.
void check_agree_on_cornell(const StageKernels& reference, const StageKernels& test, std::uint32_t seed);

}  // namespace pt::test
