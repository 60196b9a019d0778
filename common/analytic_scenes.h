// The numbers of the built-in analytic scenes, shared by builtin_scenes.cpp (which builds
// them) and the tests (which compute their images in closed form). Each scene is one whose
// every pixel is known: DESIGN.md, "Tests against closed forms".
#pragma once

#include <glm/glm.hpp>

namespace pt::analytic {

// builtin:sphere — a sphere straight ahead of a perspective camera at the origin.
struct SphereScene {
  glm::vec3 center{0.0f, 0.0f, -4.0f};
  float radius = 1.0f;
  glm::vec3 color{0.8f, 0.5f, 0.2f};  // diffuse albedo: stage1 shows it
  float yfov = 0.6f;                  // radians
};

// builtin:quad — a square turned about the view axis, under an orthographic camera.
struct QuadScene {
  float half_size = 0.6f;             // the square spans [-h, h]^2 before turning
  float angle = 0.5f;                 // radians, about +Z
  glm::vec3 color{0.2f, 0.6f, 0.9f};  // diffuse albedo
  float xmag = 1.0f, ymag = 1.0f;     // orthographic half-extents
};

// builtin:furnace — the camera inside a closed box whose every wall emits Le and reflects
// diffusely with albedo rho: stage1 sees Le everywhere, a path tracer Le / (1 - rho).
struct FurnaceScene {
  float half_size = 1.0f;
  float emission = 1.0f;
  float albedo = 0.5f;
};

}  // namespace pt::analytic
