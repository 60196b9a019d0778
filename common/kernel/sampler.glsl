// The sampler: where the estimator's uniform random numbers come from. It is shared
// machinery, not a step of the article: every stage's Monte Carlo estimator (Eq. 3 to 5)
// only asks for "a uniform number in [0, 1)" (sample_1d) or "a uniform point in the unit
// square" (sample_2d), and any source of such numbers keeps it unbiased.
//
// Two sources (FrameParams.sampler_kind, --sampler):
//   kSamplerIndependent  independent numbers: the PCG stream of rng.glsl, one per sample.
//   kSamplerSobol        randomised quasi-Monte Carlo: Owen-scrambled Sobol points
//                        (Burley 2020, "Practical Hash-based Owen Scrambling", JCGT 9(4)).
//
// The Sobol sampler. The k-th 2-D request of a path reads 2-D "slot" k: slot 0 is the
// pixel position, then one slot per 2-D request of the integrator (a light's pick and
// point, a direction, ...); the k-th 1-D request (a lobe, roulette) reads 1-D slot k, a
// shuffled and scrambled van der Corput sequence of its own. 2-D slots go in pairs,
// "blocks" of four Sobol dimensions: an even slot reads dimensions 0 and 1 (van der Corput in base 2 and Joe and Kuo's d = 2, a
// (0,2)-sequence), the odd slot after it dimensions 2 and 3. Each block gets its own random
// shuffle of the sample index (the index Owen-scrambled, which permutes it inside every
// aligned block of 2^m) and each coordinate its own Owen scramble; all keyed by hashing
// (seed, pixel, slot). So:
//   - a sample's numbers depend on (seed, pixel, sample index, slot) and nothing else:
//     sample ranges, parts and checkpoints render exactly the samples of one run;
//   - each point is uniformly distributed in the unit square and different blocks are
//     independent, so every estimator stays unbiased;
//   - the samples 0 .. 2^m - 1 of a pixel are stratified: in an even slot they form a
//     (0,m,2)-net (every elementary box of area 2^-m holds one point), in an odd slot a
//     (t,m,2)-net with t <= 2, and the four numbers of a block together a (t,m,4)-net with
//     t <= 3 (m <= 10). The pixel position and stage4's light point share block 0, so the
//     light's points are stratified across the pixel too; past block 0 the blocks are
//     padded independently (Burley 2020, section 4).
// Sample counts that are not a power of two are unbiased too, with less stratification
// (docs/sampling.md measures the cost).
// Written in the GLSL/C++ subset; per-invocation state lives in sampler_state (the
// bindings: gpu/kernel_bindings.glsl, cpu/kernel_bindings.h).
#ifndef PT_SAMPLER_GLSL
#define PT_SAMPLER_GLSL

#include "common/kernel/rng.glsl"

// The heart of an Owen scramble: a bijection of 32-bit words in which bit k of the result
// is bit k of x flipped by a pseudo-random function of the seed and of the bits BELOW k
// (additions, multiplications by odd numbers, and xor with x times an even constant only
// carry upwards). The construction of Laine and Karras 2011 with the constants of
// N. Vegdahl's improved hash, as in Burley 2020.
uint owen_permute_low_first(uint x, uint seed) {
  x ^= x * 0x3d20adeau;
  x += seed;
  x *= (seed >> 16u) | 1u;
  x ^= x * 0x05526c56u;
  x ^= x * 0x53a22864u;
  return x;
}

// Nested uniform (Owen) scrambling of a fraction's bits, read from the top: bit k flipped
// by a function of the seed and of the bits above k. Applied to a sample index it shuffles
// the points (every aligned block of 2^m indices onto an aligned block of 2^m); applied to
// a coordinate it is Owen's random scramble of a (t,m,s)-net, which keeps it a net.
uint owen_scramble(uint x, uint seed) {
  return bitfieldReverse(owen_permute_low_first(bitfieldReverse(x), seed));
}

// The first Sobol dimension of point i: the van der Corput sequence, i's bits mirrored.
uint sobol_dimension0(uint i) {
  return bitfieldReverse(i);
}

// Sobol's dimensions 1 to 3 of point i, each computed with its bits mirrored (bit 0 the
// fraction's first binary digit), the order in which owen_scramble() takes a fraction: a
// scrambled coordinate then needs one mirroring instead of three. sobol_dimension1..3 below
// mirror them back to 32-bit fractions (the tests compare those with Joe and Kuo's table).
//
// Dimension 1 (Joe and Kuo's s = 1, a = 0, m = 1): its direction numbers v_{k+1} = v_k xor
// (v_k >> 1) from v_0 = 1/2 are the rows of Pascal's triangle mod 2, so read as a polynomial
// over GF(2) (digit j the coefficient of x^j) the point is i(x + 1), i's bits the
// coefficients. (x + 1)^(2^h) = x^(2^h) + 1 mod 2, so the substitution splits each aligned
// block of 2h digits into halves and adds the upper to the lower: five shifts and masks
// instead of a loop over i's bits.
uint sobol_dimension1_mirrored(uint i) {
  i ^= (i >> 1u) & 0x55555555u;
  i ^= (i >> 2u) & 0x33333333u;
  i ^= (i >> 4u) & 0x0f0f0f0fu;
  i ^= (i >> 8u) & 0x00ff00ffu;
  i ^= (i >> 16u) & 0x0000ffffu;
  return i;
}

// Dimensions 2 and 3: the xor of the direction numbers v_k of the set bits k of i, with v_k
// from Joe and Kuo's parameters (s, a, m_1..m_s) by the recurrence v_k = (a-weighted earlier
// v) xor v_{k-s} xor (v_{k-s} >> s), mirrored (so >> becomes <<, and 1/2 becomes 1).
// Dimension 2: s = 2, a = 1, m = 1, 3 (v_k = v_{k-1} xor v_{k-2} xor (v_{k-2} >> 2)).
uint sobol_dimension2_mirrored(uint i) {
  uint result = 0u;
  uint v0 = 1u, v1 = 3u;
  for (; i != 0u; i >>= 1u) {
    result ^= v0 & (0u - (i & 1u));  // v where bit k of i is set: no branch to mispredict
    uint next = v1 ^ v0 ^ (v0 << 2u);
    v0 = v1;
    v1 = next;
  }
  return result;
}

// Dimension 3: s = 3, a = 1, m = 1, 3, 1 (v_k = v_{k-2} xor v_{k-3} xor (v_{k-3} >> 3)).
uint sobol_dimension3_mirrored(uint i) {
  uint result = 0u;
  uint v0 = 1u, v1 = 3u, v2 = 4u;
  for (; i != 0u; i >>= 1u) {
    result ^= v0 & (0u - (i & 1u));
    uint next = v1 ^ v0 ^ (v0 << 3u);
    v0 = v1;
    v1 = v2;
    v2 = next;
  }
  return result;
}

// Dimensions 2 and 3 of point i together, mirrored (x: dimension 2, y: dimension 3), the
// way the sampler takes them. Below 2^16, where every shuffled index of the first 65,536
// samples lies (shuffle_index), the sums above need only v_0 .. v_15, which have at most
// 16 bits: one word holds both dimensions' v_k (dimension 2 in its low half, 3 in its high
// half, the constants below, from the recurrences above), and each bit of i costs one mask
// and one xor for the two, with no recurrence to run. Larger i take the loops.
uvec2 sobol_dimensions23_mirrored(uint i) {
  if (i > 0xffffu) return uvec2(sobol_dimension2_mirrored(i), sobol_dimension3_mirrored(i));
  uint r = 0u;
  r ^= 0x00010001u & (0u - (i & 1u));
  r ^= 0x00030003u & (0u - ((i >> 1u) & 1u));
  r ^= 0x00040006u & (0u - ((i >> 2u) & 1u));
  r ^= 0x000a0009u & (0u - ((i >> 3u) & 1u));
  r ^= 0x001f0017u & (0u - ((i >> 4u) & 1u));
  r ^= 0x002e003au & (0u - ((i >> 5u) & 1u));
  r ^= 0x00450071u & (0u - ((i >> 6u) & 1u));
  r ^= 0x00c900a3u & (0u - ((i >> 7u) & 1u));
  r ^= 0x011b0116u & (0u - ((i >> 8u) & 1u));
  r ^= 0x02a40339u & (0u - ((i >> 9u) & 1u));
  r ^= 0x079a0677u & (0u - ((i >> 10u) & 1u));
  r ^= 0x0b6709aau & (0u - ((i >> 11u) & 1u));
  r ^= 0x101e1601u & (0u - ((i >> 12u) & 1u));
  r ^= 0x302d3903u & (0u - ((i >> 13u) & 1u));
  r ^= 0x40417706u & (0u - ((i >> 14u) & 1u));
  r ^= 0xa0c3aa09u & (0u - ((i >> 15u) & 1u));
  return uvec2(r & 0xffffu, r >> 16u);
}

// Dimensions 1 to 3 of point i as 32-bit fractions.
uint sobol_dimension1(uint i) {
  return bitfieldReverse(sobol_dimension1_mirrored(i));
}
uint sobol_dimension2(uint i) {
  return bitfieldReverse(sobol_dimensions23_mirrored(i).x);
}
uint sobol_dimension3(uint i) {
  return bitfieldReverse(sobol_dimensions23_mirrored(i).y);
}

// The largest float below 1 (1 - 2^-24): where a number in [0, 1) is clamped after arithmetic.
const float kOneMinusEpsilon = 0.99999994f;

// A 32-bit fraction as a float in [0, 1): its top 24 bits, so 1 is never returned.
float unit_float(uint bits) {
  return float(bits >> 8u) * (1.0f / 16777216.0f);
}

// The shuffle of a pixel's sample indices: a nested uniform scramble of the index's low 16
// bits (every aligned block of 2^m indices, m <= 16, onto an aligned block of 2^m), its
// high bits kept. Shuffling 16 bits rather than 32 keeps the shuffled index of the first
// 65,536 samples below 2^16, so that the Sobol loops above run 16 times, not 32.
uint shuffle_index(uint index, uint seed) {
  return (owen_scramble(index << 16u, seed) >> 16u) | (index & 0xffff0000u);
}

// Point `sample_index` of 2-D slot `slot` of the pixel keyed `pixel_key`: two Owen-scrambled
// Sobol coordinates as 32-bit fractions. Slots 2b and 2b + 1 make block b: the same
// shuffle of the sample index (seeded by the block), then Sobol dimensions 0 and 1 for the
// even slot and 2 and 3 for the odd one, each coordinate scrambled with its own seed. So
// the even slot is a (0,2)-sequence, the odd one a (t,2)-sequence with t <= 2, and the
// block's four numbers are stratified together (a (t,4)-sequence, t <= 3 for the first
// 1024 samples). The first coordinate of an even slot, owen_scramble(sobol_dimension0(i),
// seed), is written without its two mirrorings, which cancel.
uvec2 sobol_slot_point(uint pixel_key, uint slot, uint sample_index) {
  uint block_seed = pcg_hash(pixel_key + (slot >> 1u) * 0x9e3779b9u);
  uint i = shuffle_index(sample_index, block_seed);
  uint seed_x = pcg_hash(block_seed ^ (((slot & 1u) + 1u) * 0x85ebca6bu));
  uint seed_y = pcg_hash(seed_x);
  // owen_scramble(sobol_dimensionN(i), seed) = bitfieldReverse(owen_permute_low_first(
  // sobol_dimensionN_mirrored(i), seed)): the mirrorings in between cancel.
  if ((slot & 1u) == 0u) {
    return uvec2(bitfieldReverse(owen_permute_low_first(i, seed_x)),
                 bitfieldReverse(owen_permute_low_first(sobol_dimension1_mirrored(i), seed_y)));
  }
  uvec2 d = sobol_dimensions23_mirrored(i);
  return uvec2(bitfieldReverse(owen_permute_low_first(d.x, seed_x)),
               bitfieldReverse(owen_permute_low_first(d.y, seed_y)));
}

// Number `sample_index` of the 1-D set `slot` of the pixel keyed `pixel_key`: the van der
// Corput sequence with its own shuffle and Owen scramble, a (0,1)-sequence, as a 32-bit
// fraction. (owen_scramble(sobol_dimension0(i), seed) without the mirrorings that cancel.)
uint sobol_1d_point(uint pixel_key, uint slot, uint sample_index) {
  uint seed = pcg_hash((pixel_key ^ 0x1b873593u) + slot * 0x9e3779b9u);
  return bitfieldReverse(owen_permute_low_first(shuffle_index(sample_index, seed), pcg_hash(seed)));
}

// Starts one sample of one pixel: what sample_1d and sample_2d read until the next call.
// sampler_state: (the pixel's key, the sample index, the next 2-D slot in the low 16 bits
// and the next 1-D slot in the high 16, the sampler). 2-D and 1-D requests count apart, so
// that a 1-D choice (a lobe, roulette) between two 2-D requests does not move the second
// out of the first one's block: the pixel position and the first light point (or stage2's
// and stage3's first direction) share block 0. Past 65,536 requests of a kind (32,768
// bounces) the slots wrap around. Only the independent sampler reads, and so seeds, a PCG stream.
void start_sample(uint pixel_index, uint sample_index, uint seed, uint kind) {
  if (kind == kSamplerIndependent) rng_seed(pixel_index, sample_index, seed);
  sampler_state = uvec4(pcg_hash(pixel_index ^ pcg_hash(seed ^ 0x85ebca6bu)), sample_index, 0u, kind);
}

// The next uniform number in [0, 1) of this sample: the next 1-D set.
float sample_1d() {
  if (sampler_state.w == kSamplerIndependent) return rng_next_float();
  uint slot = sampler_state.z >> 16u;
  sampler_state.z += 0x10000u;
  return unit_float(sobol_1d_point(sampler_state.x, slot, sampler_state.y));
}

// The next uniform point in [0, 1)^2 of this sample: the next 2-D slot.
vec2 sample_2d() {
  if (sampler_state.w == kSamplerIndependent) return rng_next_vec2();
  uint slot = sampler_state.z & 0xffffu;
  sampler_state.z = (sampler_state.z & 0xffff0000u) | ((slot + 1u) & 0xffffu);
  uvec2 bits = sobol_slot_point(sampler_state.x, slot, sampler_state.y);
  return vec2(unit_float(bits.x), unit_float(bits.y));
}

#endif  // PT_SAMPLER_GLSL
