// Checkpoint and resume of a long render (--checkpoint SECONDS, --resume [PATH]): the
// film's running sums, its sample count, the pass schedule's position (which is also the
// random number generator's: every sample's random numbers follow from the seed and the
// sample's index) and the event counters, written atomically beside the image as
// <out>.ckpt. A resumed render adds the same passes an uninterrupted one would, so on the
// CPU backend the result equals the uninterrupted render bit for bit.
// Not part of the article: the machinery of the stage programs (the article's estimators
// are sums of independent samples, which is what makes stopping and continuing exact).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "common/render/render.h"

namespace pt {

struct Scene;

// A 64-bit FNV-1a hash of `bytes` bytes (the hash the two below are made of).
std::uint64_t bytes_hash(const void* data, std::size_t bytes);

// A 64-bit FNV-1a hash of the scene's arrays (triangles, spheres, materials, lights): the
// same content gives the same hash whatever file or path it came from.
std::uint64_t scene_hash(const Scene& scene);

// A 64-bit FNV-1a hash of everything that determines the image apart from the sample count:
// the stage, the scene's arrays and camera, the image size, seed, sky, roulette, depth cap,
// the kernel choice (--all-features) and the first sample (--samples). Two renders with the same key and seed add up
// the same samples.
std::uint64_t render_key(const char* stage, const Scene& scene, const RenderSettings& settings);

// Writes the render's state atomically (a temporary file in the same folder, fsync, rename).
// Throws pt::Error(kExitOutput) if it cannot be written.
void save_checkpoint(const std::string& path, std::uint64_t key, const char* stage, const RenderResult& state);

// Reads a checkpoint written by save_checkpoint for a render with this key and size. A
// missing file, a damaged or truncated one, or one of a different render is refused with
// pt::Error(kExitBadOption) and one line saying what is wrong and what to do.
RenderResult load_checkpoint(const std::string& path, std::uint64_t key, const char* stage, int width, int height,
                             std::uint64_t first_sample = 0);

}  // namespace pt
