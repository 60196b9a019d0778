// The camera's clip start (common/kernel/camera.glsl, Camera::clip_start): a ray of the
// article's Eq. (2) starts on the plane that far along the view axis instead of at the eye,
// in the same direction, so what lies between the eye and that plane is not seen. smallpt's
// camera needs it: it stands behind the room's black front wall and starts its rays 140
// units ahead (builtin:smallpt).
#include <catch2/catch.hpp>

#include <cmath>

#include "common/render/render.h"
#include "common/scene/scene.h"
#include "common/scene/scene_loading.h"
#include "cpu/kernel_prelude.h"

namespace {  // internal linkage: each test file compiles its own copy of the kernel code
namespace kernel {
#include "cpu/kernel_begin.h"
#include "common/kernel/camera.glsl"
#include "common/kernel/intersect.glsl"
#include "cpu/kernel_support.h"
#include "tests/support/kernel_scene_binding.h"
}  // namespace kernel

const float kAspect = 64.0f / 48.0f;
}  // namespace

TEST_CASE("camera clip start: rays keep their directions and start on the plane that far along the view axis",
          "[camera]") {
  pt::Scene scene = pt::load_scene("builtin:smallpt");
  pt::Camera clipped = pt::make_camera(scene, kAspect);
  REQUIRE(clipped.clip_start == 140.0f);
  pt::Camera eye = clipped;
  eye.clip_start = 0.0f;
  for (int j = 0; j < 12; j++) {
    for (int i = 0; i < 16; i++) {
      glm::vec2 film((i + 0.5f) / 16.0f, (j + 0.5f) / 12.0f);
      kernel::Ray a = kernel::camera_ray(eye, film);
      kernel::Ray b = kernel::camera_ray(clipped, film);
      // No clip start: the ray starts at the eye, bit for bit (every glTF camera).
      CHECK(a.origin == eye.origin);
      CHECK(a.dir == b.dir);
      // The start lies on the plane 140 ahead, on the eye's ray through that film point.
      glm::vec3 offset = b.origin - eye.origin;
      CHECK(glm::dot(offset, eye.forward) == Approx(140.0f).epsilon(1e-5));
      CHECK(glm::length(glm::cross(offset, a.dir)) < 1e-4f * glm::length(offset));
    }
  }
  // Orthographic: the whole view moves forward by the clip start.
  pt::Camera ortho = eye;
  ortho.kind = pt::kCameraOrthographic;
  ortho.extent_x = 2.0f, ortho.extent_y = 1.5f;
  kernel::Ray o0 = kernel::camera_ray(ortho, glm::vec2(0.25f, 0.75f));
  ortho.clip_start = 3.0f;
  kernel::Ray o3 = kernel::camera_ray(ortho, glm::vec2(0.25f, 0.75f));
  CHECK(o3.dir == o0.dir);
  CHECK(glm::length(o3.origin - (o0.origin + 3.0f * ortho.forward)) < 1e-4f);
}

TEST_CASE("camera clip start: smallpt's camera sees the room past its black front wall, and only the wall without it",
          "[camera]") {
  pt::Scene scene = pt::load_scene("builtin:smallpt");
  kernel::bind_scene(scene);
  kernel::params.scene_radius = pt::make_frame_params(scene, pt::RenderSettings{}).scene_radius;
  // The front wall: the black sphere whose surface is the plane z = 170 near the room.
  uint front = ~0u;
  for (size_t k = 0; k < scene.spheres.size(); k++) {
    const pt::Sphere& s = scene.spheres[k];
    if (s.radius > 1e4f && std::abs(s.center.z - (170.0f - 1e5f)) < 1.0f) front = uint(k);
  }
  REQUIRE(front != ~0u);
  pt::Camera clipped = pt::make_camera(scene, kAspect);
  pt::Camera eye = clipped;
  eye.clip_start = 0.0f;
  int front_seen_clipped = 0, front_seen_eye = 0, rays = 0;
  for (int j = 0; j < 48; j++) {
    for (int i = 0; i < 64; i++, rays++) {
      glm::vec2 film((i + 0.5f) / 64.0f, (j + 0.5f) / 48.0f);
      kernel::Hit h = kernel::intersect_scene(kernel::camera_ray(clipped, film), kernel::kInfinity);
      kernel::Hit e = kernel::intersect_scene(kernel::camera_ray(eye, film), kernel::kInfinity);
      REQUIRE(h.kind == pt::kPrimSphere);
      if (h.prim == front) front_seen_clipped++;
      if (e.kind == pt::kPrimSphere && e.prim == front) front_seen_eye++;
    }
  }
  CHECK(front_seen_clipped == 0);
  CHECK(front_seen_eye == rays);
}
