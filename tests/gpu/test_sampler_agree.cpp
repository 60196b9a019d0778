// The sampler (common/kernel/sampler.glsl) gives the same numbers on the CPU and the GPU, bit
// for bit: a kernel whose radiance is the sampler's numbers (tests/support/sampler_probe.glsl)
// renders 1-spp images on both backends, for several sample indices, seeds and both samplers.
#include <catch2/catch.hpp>

#include <cstring>

#include "common/scene/scene_loading.h"
#include "sampler_probe/kernels.h"
#include "tests/support/test_render.h"

using namespace pt;
using namespace pt::test;

namespace {

// The bits of the float a 1-sample pixel holds (the film keeps the sum in double exactly).
std::uint32_t bits(double v) {
  float f = float(v);
  std::uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

}  // namespace

TEST_CASE("sampler: the CPU and the GPU give the same numbers bit for bit", "[sampler][gpu]") {
  Scene scene = make_builtin_scene("quad");
  for (std::uint32_t kind : {kSamplerSobol, kSamplerIndependent}) {
    for (std::uint64_t first : {0ull, 1ull, 7ull, 1000ull, 65535ull, 4294967294ull}) {
      RenderSettings s = settings(13, 11, 1, 0x9e37u + std::uint32_t(first));
      s.first_sample = first;
      s.sampler = kind;
      Film cpu = render_on("cpu", sampler_probe::kernels(), scene, s).film;
      Film gpu = render_on("gpu", sampler_probe::kernels(), scene, s).film;
      int differing = 0;
      for (int y = 0; y < cpu.height(); y++) {
        for (int x = 0; x < cpu.width(); x++) {
          for (int c = 0; c < 3; c++) differing += bits(cpu.mean(x, y)[c]) != bits(gpu.mean(x, y)[c]);
        }
      }
      INFO((kind == kSamplerSobol ? "sobol" : "independent") << ", sample " << first);
      CHECK(differing == 0);
    }
  }
}
