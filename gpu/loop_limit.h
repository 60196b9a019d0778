// The GPU backend's answer to lavapipe's loop limit: gpu/kernel_main.glsl counts the pixels
// whose loops the driver cut short in a counter of the GPU's own; a pass with such pixels is
// redone one sample per invocation, and one still cut is reported (PassResult::cut_short).
// Not part of the article: machinery for one Vulkan driver (Mesa's lavapipe).
#pragma once

#include <functional>
#include <span>
#include <string>

#include <glm/glm.hpp>

#include "common/render/backend.h"

namespace pt::gpu {

// The counter gpu/kernel_main.glsl adds to, after the kernels' own (scene_types.h, kCounter*):
// the GPU's counter buffer holds kGpuCounterCount values.
constexpr uint kCounterLoopLimit = kCounterCount;
constexpr uint kGpuCounterCount = kCounterCount + 1;

// PassResult::cut_short for a pass in which the driver cut the loops of `cut_pixels` pixels:
// "" for none, else what happened and what to do, in one line.
std::string loop_limit_message(uint cut_pixels);

// The pass `params` as params.sample_count passes of one sample each, each run by `run` into
// `out` (the same sample indices, so the same samples), added up as render_pixel() adds its
// samples: the radiance sums, and the roots of the sums of squared luminance as the root of
// their squares' sum. The counters as PassResult::add merges them.
PassResult run_one_sample_at_a_time(const FrameParams& params, std::span<glm::vec4> out,
                                    const std::function<PassResult(const FrameParams&)>& run);

}  // namespace pt::gpu
