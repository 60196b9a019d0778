// The Vulkan backend's shared device (gpu/device_session.h; not part of the article:
// machinery of issue #51): backends made in turn on one DeviceSession compile each kernel
// once per feature set and render exactly what a backend on a device of its own renders.
#include <catch2/catch.hpp>

#include <memory>

#include "common/scene/scene_loading.h"
#include "gpu/device_session.h"
#include "gpu/gpu_backend.h"
#include "stage1_raycast/kernels.h"
#include "stage4_direct_indirect/kernels.h"
#include "tests/support/test_render.h"

using namespace pt;
using namespace pt::test;

namespace {

RenderResult render_with(std::unique_ptr<Backend> backend, const char* scene_name) {
  return render(*backend, make_builtin_scene(scene_name), settings(32, 24, 4, 5));
}

bool same_pixels(const Film& a, const Film& b) {
  if (a.width() != b.width() || a.height() != b.height()) return false;
  for (int y = 0; y < a.height(); y++) {
    for (int x = 0; x < a.width(); x++) {
      if (a.mean(x, y) != b.mean(x, y)) return false;
    }
  }
  return true;
}

}  // namespace

TEST_CASE("device session: a second backend on the device compiles no kernel again and renders the same image",
          "[gpu][device_session]") {
  auto session = std::make_shared<gpu::DeviceSession>("");
  RenderResult first = render_with(gpu::create_backend(stage4::kernels(), session), "cornell");
  const std::size_t compiled = session->compiled();
  CHECK(compiled >= 1);
  RenderResult second = render_with(gpu::create_backend(stage4::kernels(), session), "cornell");
  CHECK(session->compiled() == compiled);
  CHECK(same_pixels(first.film, second.film));
  // A backend on a device of its own (what the stage programs make) renders the same.
  RenderResult alone = render_with(gpu::create_backend(stage4::kernels(), ""), "cornell");
  CHECK(same_pixels(first.film, alone.film));
}

TEST_CASE("device session: another stage or another feature set compiles a kernel of its own",
          "[gpu][device_session]") {
  auto session = std::make_shared<gpu::DeviceSession>("");
  render_with(gpu::create_backend(stage1::kernels(), session), "cornell");
  const std::size_t after_cornell = session->compiled();
  // The same scene through stage4's kernel: another kernel, though the features are the same.
  render_with(gpu::create_backend(stage4::kernels(), session), "cornell");
  CHECK(session->compiled() == after_cornell + 1);
  // Stage1 again on a scene of spheres: other features, another program; the Cornell box's
  // program is still there (one more, not a replacement).
  RenderResult spheres = render_with(gpu::create_backend(stage1::kernels(), session), "sphere");
  CHECK(session->compiled() == after_cornell + 2);
  RenderResult spheres_alone = render_with(gpu::create_backend(stage1::kernels(), ""), "sphere");
  CHECK(same_pixels(spheres.film, spheres_alone.film));
}
