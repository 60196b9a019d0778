// Random numbers that are the same on the CPU and the GPU: a PCG generator (O'Neill 2014,
// the 32-bit RXS-M-XS output) whose state is seeded by hashing pixel, sample index and
// seed (Jarzynski & Olano 2020, "Hash Functions for GPU Rendering"). Every sample of every
// pixel has its own stream, so images do not depend on how the work is split.
#ifndef PT_RNG_GLSL
#define PT_RNG_GLSL

uint pcg_permute(uint state) {
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

uint pcg_hash(uint v) {
  return pcg_permute(v * 747796405u + 2891336453u);
}

// Starts the stream of one sample of one pixel.
void rng_seed(uint pixel_index, uint sample_index, uint seed) {
  rng_state = pcg_hash(pixel_index ^ pcg_hash(sample_index ^ pcg_hash(seed)));
}

uint rng_next_uint() {
  rng_state = rng_state * 747796405u + 2891336453u;
  return pcg_permute(rng_state);
}

// A float uniformly distributed in [0, 1): 24 random bits, so 1 is never returned.
float rng_next_float() {
  return float(rng_next_uint() >> 8u) * (1.0f / 16777216.0f);
}

// A point uniformly distributed in [0, 1)^2: two floats of the stream, x first.
vec2 rng_next_vec2() {
  float a = rng_next_float();
  return vec2(a, rng_next_float());
}

#endif  // PT_RNG_GLSL
