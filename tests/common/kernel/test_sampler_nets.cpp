// The sampler (common/kernel/sampler.glsl; docs/sampling.md, "What stays stratified"),
// compiled as the CPU kernels compile it: Owen scrambling keeps every set a net, each
// pixel's even slots (0,m,2)-nets, a block's odd slot and its four numbers together nets
// with the t of Sobol's own points. The Sobol points and the scrambling themselves:
// test_sampler.cpp.
#include <catch2/catch.hpp>

#include <functional>
#include <random>
#include <vector>

#include "cpu/kernel_prelude.h"

namespace {  // internal linkage: each test file compiles its own copy of the kernel code
namespace kernel {
#include "cpu/kernel_begin.h"
#include "common/kernel/sampler.glsl"
}  // namespace kernel
}  // namespace

using kernel::uint;

namespace {

// The point `index` of slot `slot` of the pixel keyed `key`, as the kernel's sample_2d
// returns it.
glm::vec2 point(uint key, uint slot, uint index) {
  glm::uvec2 bits = kernel::sobol_slot_point(key, slot, index);
  return glm::vec2(kernel::unit_float(bits.x), kernel::unit_float(bits.y));
}

// Whether n = 2^m points form a (0,m,2)-net: every elementary box of 2^-a by 2^-(m-a)
// holds exactly one of them.
bool is_02_net(const std::vector<glm::vec2>& points, int m) {
  for (int a = 0; a <= m; a++) {
    std::vector<int> count(std::size_t(1) << m, 0);
    for (glm::vec2 p : points) {
      std::size_t bx = std::size_t(double(p.x) * double(1u << a));
      std::size_t by = std::size_t(double(p.y) * double(1u << (m - a)));
      if (++count[(bx << (m - a)) | by] > 1) return false;
    }
  }
  return true;
}

// The smallest t for which 2^m points in [0,1)^d, given as their leading m bits per
// coordinate, form a (t,m,d)-net: every elementary box of volume 2^(t-m) holds 2^t points
// (equivalently, the 2^(m-t) boxes of each shape are all hit).
int net_t_value(const std::vector<std::vector<uint>>& points, int m, int d) {
  for (int t = 0; t <= m; t++) {
    bool ok = true;
    std::vector<int> shape(d, 0);
    // Every split of m - t bits among the d coordinates.
    std::function<void(int, int)> visit = [&](int axis, int left) {
      if (!ok) return;
      if (axis == d - 1) {
        shape[axis] = left;
        std::vector<char> hit(std::size_t(1) << (m - t), 0);
        for (const auto& p : points) {
          std::size_t box = 0;
          for (int k = 0; k < d; k++) box = (box << shape[k]) | (p[k] >> (m - shape[k]));
          hit[box] = 1;
        }
        for (char h : hit) ok = ok && h;
        return;
      }
      for (int a = 0; a <= left; a++) shape[axis] = a, visit(axis + 1, left - a);
    };
    visit(0, m - t);
    if (ok) return t;
  }
  return m;
}

// The leading m bits of the 2^m points `first` ... of one pixel's block (slots 2b, 2b + 1),
// coordinates `dims` of its four (0, 1 of the even slot, 2, 3 of the odd one).
std::vector<std::vector<uint>> block_bits(uint key, uint block, uint first, int m, const std::vector<int>& dims) {
  std::vector<std::vector<uint>> out;
  for (uint i = 0; i < (1u << m); i++) {
    glm::uvec2 even = kernel::sobol_slot_point(key, 2 * block, first + i);
    glm::uvec2 odd = kernel::sobol_slot_point(key, 2 * block + 1, first + i);
    uint all[4] = {even.x, even.y, odd.x, odd.y};
    std::vector<uint> p;
    for (int d : dims) p.push_back(m == 0 ? 0u : all[d] >> (32 - m));
    out.push_back(p);
  }
  return out;
}

// The same of the unscrambled Sobol points 0 ... 2^m - 1, dimensions `dims`.
std::vector<std::vector<uint>> sobol_bits(int m, const std::vector<int>& dims) {
  std::vector<std::vector<uint>> out;
  for (uint i = 0; i < (1u << m); i++) {
    uint all[4] = {kernel::sobol_dimension0(i), kernel::sobol_dimension1(i), kernel::sobol_dimension2(i),
                   kernel::sobol_dimension3(i)};
    std::vector<uint> p;
    for (int d : dims) p.push_back(m == 0 ? 0u : all[d] >> (32 - m));
    out.push_back(p);
  }
  return out;
}

}  // namespace

TEST_CASE("sampler: each pixel's even slots are (0,m,2)-nets in every aligned block of 2^m samples", "[sampler]") {
  std::mt19937 rng(12);
  for (int m = 0; m <= 12; m++) {
    for (int set = 0; set < 6; set++) {
      uint key = rng();
      for (uint slot : {0u, 2u, 6u}) {
        for (uint block : {0u, 1u, 5u, 30u}) {
          std::vector<glm::vec2> pts;
          for (uint i = 0; i < (1u << m); i++) pts.push_back(point(key, slot, block * (1u << m) + i));
          INFO("m " << m << ", key " << key << ", slot " << slot << ", samples from " << block * (1u << m));
          REQUIRE(is_02_net(pts, m));
        }
      }
    }
  }
  // The control: independent points are not nets (the test can fail).
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  std::vector<glm::vec2> random_points;
  for (int i = 0; i < 256; i++) random_points.push_back(glm::vec2(u01(rng), u01(rng)));
  CHECK_FALSE(is_02_net(random_points, 8));
}

TEST_CASE("sampler: a block's odd slot and its four numbers together are nets as good as Sobol's own", "[sampler]") {
  // Owen scrambling keeps a (t,m,s)-net a (t,m,s)-net: the scrambled points of dimensions
  // 2-3 (the odd slot) and 0-3 (the whole block) have the t of the unscrambled Sobol points
  // 0 ... 2^m - 1 (measured: t <= 2 in 2-D, t <= 3 in 4-D for m <= 10), in every aligned
  // block of samples; and the 4-D t is far below that of independent points.
  std::mt19937 rng(13);
  for (int m = 1; m <= 9; m++) {
    int t2 = net_t_value(sobol_bits(m, {2, 3}), m, 2), t4 = net_t_value(sobol_bits(m, {0, 1, 2, 3}), m, 4);
    CHECK(t2 <= 2);
    CHECK(t4 <= 3);
    for (int set = 0; set < 3; set++) {
      uint key = rng();
      for (uint block : {0u, 3u}) {
        uint first = block * (1u << m);
        INFO("m " << m << ", key " << key << ", samples from " << first << ": Sobol's t " << t2 << " (2-D), " << t4
                  << " (4-D)");
        CHECK(net_t_value(block_bits(key, block, first, m, {2, 3}), m, 2) == t2);
        CHECK(net_t_value(block_bits(key, block, first, m, {0, 1, 2, 3}), m, 4) == t4);
      }
    }
  }
  // The control: independent points in 4-D are worse nets than Sobol's (the test can fail).
  for (int m : {6, 8}) {
    std::vector<std::vector<uint>> random_points;
    for (int i = 0; i < (1 << m); i++) {
      random_points.push_back({uint(rng() >> (32 - m)), uint(rng() >> (32 - m)), uint(rng() >> (32 - m)), uint(rng() >> (32 - m))});
    }
    CHECK(net_t_value(random_points, m, 4) > net_t_value(sobol_bits(m, {0, 1, 2, 3}), m, 4));
  }
}
