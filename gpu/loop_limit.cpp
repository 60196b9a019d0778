// The GPU backend's answer to lavapipe's loop limit (loop_limit.h): the message, and a pass
// run one sample per invocation. Not part of the article: machinery for one Vulkan driver.
#include "gpu/loop_limit.h"

#include <cmath>
#include <vector>

namespace pt::gpu {

std::string loop_limit_message(uint cut_pixels) {
  if (cut_pixels == 0) return "";
  return "the Vulkan driver cut the loops of " + std::to_string(cut_pixels) +
         " pixels short (lavapipe ends an invocation after 65535 loop iterations); use --backend cpu, a lower "
         "albedo or fewer triangles";
}

PassResult run_one_sample_at_a_time(const FrameParams& params, std::span<glm::vec4> out,
                                    const std::function<PassResult(const FrameParams&)>& run) {
  std::vector<glm::dvec3> radiance(out.size(), glm::dvec3(0.0));
  std::vector<double> squares(out.size(), 0.0);  // the sums of squared luminance
  PassResult result;
  for (uint i = 0; i < params.sample_count; i++) {
    FrameParams one = params;
    one.first_sample = params.first_sample + i;
    one.sample_count = 1u;
    PassResult part = run(one);
    for (std::size_t p = 0; p < out.size(); p++) {
      const double root = double(out[p][kPassRootSumSquares]);
      radiance[p] += glm::dvec3(out[p]);
      squares[p] += root * root;
    }
    result.add(part);
  }
  for (std::size_t p = 0; p < out.size(); p++) {
    out[p] = glm::vec4(glm::vec3(radiance[p]), 0.0f);
    out[p][kPassRootSumSquares] = float(std::sqrt(squares[p]));
  }
  return result;
}

}  // namespace pt::gpu
