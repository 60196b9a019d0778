// The sampler (common/kernel/sampler.glsl; docs/sampling.md), compiled as the CPU kernels
// compile it: the unscrambled Sobol points are the published ones (Joe and Kuo's direction
// numbers), and Owen scrambling is nested. That the scrambled points stay nets:
// test_sampler_nets.cpp; that a sample's numbers are uniform and independent and integrate
// well: test_sampler_statistics.cpp. The CPU and the GPU giving the same numbers is
// tests/gpu/test_sampler_agree.cpp.
#include <catch2/catch.hpp>

#include <random>
#include <vector>

#include "cpu/kernel_prelude.h"

namespace {  // internal linkage: each test file compiles its own copy of the kernel code
namespace kernel {
#include "cpu/kernel_begin.h"
#include "common/kernel/sampler.glsl"
}  // namespace kernel
}  // namespace

namespace {

using kernel::uint;

// Sobol's second dimension from Joe and Kuo's parameters for it (d = 2: s = 1, a = 0,
// m_1 = 1), by their general recurrence, independent of the kernel's shortcut:
// v_k = v_{k-s} xor (v_{k-s} >> s) xor (the a-weighted earlier v), as 32-bit fractions.
std::vector<uint> joe_kuo_directions(int s, uint a, const std::vector<uint>& m) {
  std::vector<uint> v(33, 0u);
  for (int k = 1; k <= s; k++) v[k] = m[k - 1] << (32 - k);
  for (int k = s + 1; k <= 32; k++) {
    v[k] = v[k - s] ^ (v[k - s] >> s);
    for (int j = 1; j < s; j++) {
      if ((a >> (s - 1 - j)) & 1u) v[k] ^= v[k - j];
    }
  }
  return v;
}

uint sobol_from_directions(const std::vector<uint>& v, uint i) {
  uint x = 0u;
  for (int k = 1; i != 0u; k++, i >>= 1u) {
    if (i & 1u) x ^= v[k];
  }
  return x;
}

}  // namespace

TEST_CASE("sampler: the unscrambled Sobol points are the published ones", "[sampler]") {
  // Joe and Kuo, "Notes on generating Sobol' sequences" (2008), the first points of
  // dimensions 1 to 4 in Gray-code order (point n is x_{n xor (n >> 1)}).
  const double dim1[] = {0, 0.5, 0.75, 0.25, 0.375, 0.875, 0.625, 0.125, 0.1875, 0.6875, 0.9375, 0.4375};
  const double dim2[] = {0, 0.5, 0.25, 0.75, 0.375, 0.875, 0.125, 0.625, 0.3125, 0.8125, 0.0625, 0.5625};
  const double dim3[] = {0, 0.5, 0.25, 0.75, 0.625, 0.125, 0.875, 0.375, 0.9375, 0.4375, 0.6875, 0.1875};
  const double dim4[] = {0, 0.5, 0.25, 0.75, 0.875, 0.375, 0.625, 0.125, 0.4375, 0.9375, 0.1875, 0.6875};
  for (uint n = 0; n < 12; n++) {
    uint g = n ^ (n >> 1u);
    INFO("point " << n);
    CHECK(double(kernel::sobol_dimension0(g)) / 4294967296.0 == dim1[n]);
    CHECK(double(kernel::sobol_dimension1(g)) / 4294967296.0 == dim2[n]);
    CHECK(double(kernel::sobol_dimension2(g)) / 4294967296.0 == dim3[n]);
    CHECK(double(kernel::sobol_dimension3(g)) / 4294967296.0 == dim4[n]);
  }
  // Every point, from Joe and Kuo's parameters by the general recurrence; dimension 1 is
  // the identity matrix (s = 0 in their table: the van der Corput sequence). Dimensions 2
  // and 3 come from the packed word of sobol_dimensions23_mirrored below 2^16 and from the
  // loops above it: the loop over i below checks the first, the four large i the second.
  // Their rows: d = 2: s = 1, a = 0, m = 1; d = 3: s = 2, a = 1, m = 1 3; d = 4: s = 3, a = 1, m = 1 3 1.
  std::vector<uint> v = joe_kuo_directions(1, 0u, {1u});
  std::vector<uint> v3 = joe_kuo_directions(2, 1u, {1u, 3u});
  std::vector<uint> v4 = joe_kuo_directions(3, 1u, {1u, 3u, 1u});
  std::vector<uint> identity(33, 0u);
  for (int k = 1; k <= 32; k++) identity[k] = 1u << (32 - k);
  for (uint i = 0; i < (1u << 16); i++) {
    REQUIRE(kernel::sobol_dimension1(i) == sobol_from_directions(v, i));
    REQUIRE(kernel::sobol_dimension0(i) == sobol_from_directions(identity, i));
    REQUIRE(kernel::sobol_dimension2(i) == sobol_from_directions(v3, i));
    REQUIRE(kernel::sobol_dimension3(i) == sobol_from_directions(v4, i));
  }
  for (uint i : {0xffffffffu, 0x80000000u, 0x12345678u, 0xdeadbeefu}) {
    CHECK(kernel::sobol_dimension1(i) == sobol_from_directions(v, i));
    CHECK(kernel::sobol_dimension2(i) == sobol_from_directions(v3, i));
    CHECK(kernel::sobol_dimension3(i) == sobol_from_directions(v4, i));
  }
}

TEST_CASE("sampler: Owen scrambling is nested: two fractions that share k leading bits share exactly k after it",
          "[sampler]") {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 20000; trial++) {
    uint seed = rng(), x = rng();
    int k = int(rng() % 32u);
    uint y = x ^ (0x80000000u >> k);           // differ first at bit k from the top
    y ^= (rng() & ((0x80000000u >> k) - 1u));  // and anywhere below it
    uint sx = kernel::owen_scramble(x, seed), sy = kernel::owen_scramble(y, seed);
    uint diff = sx ^ sy;
    INFO("x " << x << ", y " << y << ", seed " << seed << ", k " << k);
    REQUIRE(diff != 0u);
    REQUIRE(__builtin_clz(diff) == k);
  }
}
