// The numbers of the built-in analytic scenes, shared by builtin_scenes.cpp (which builds
// them) and the tests (which compute their images in closed form). Each scene is one whose
// every pixel is known: docs/testing.md.
#pragma once

#include <glm/glm.hpp>

#include "common/scene/scene.h"

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

// builtin:furnace_sphere — the camera at the centre of a sphere whose inside emits Le
// (double-sided) and reflects with albedo rho: Le / (1 - rho) everywhere. Unlike the box,
// it has no edges: light sampling's cos_x cos_y / d^2 is the constant 1 / (4 r^2) there.
struct FurnaceSphereScene {
  float radius = 1.0f;
  float emission = 1.0f;
  float albedo = 0.5f;
};

// builtin:furnace_mesh — the furnace of FurnaceSphereScene as a mesh: the inside of an
// icosphere of 20 n^2 triangles (add_icosphere; n = 256: 1,310,720), each emitting Le on
// both sides and reflecting with albedo rho. Any closed surface gives Le / (1 - rho) inside,
// whatever its tessellation, so the image is known through a BVH of a million triangles.
struct FurnaceMeshScene {
  int n = 256;
  float radius = 1.0f;
  float emission = 1.0f;
  float albedo = 0.5f;
};

// builtin:floor_light — a diffuse floor (y = 0) under a square emitter facing down, seen
// from below the emitter by an orthographic camera looking straight down. The emitter is
// black, the floor flat: light reaches the floor once, and each point's radiance is
// albedo / pi x irradiance, the irradiance by Lambert's polygon formula.
struct FloorLightScene {
  float floor_half = 20.0f;            // the floor spans [-h, h]^2 in x, z
  float albedo = 0.5f;
  float light_half = 0.5f;             // the emitter spans [-a, a]^2 in x, z ...
  float light_height = 1.0f;           // ... at this height
  glm::vec3 emission{4.0f, 4.0f, 4.0f};
  float camera_height = 0.5f;          // between floor and emitter
  float view_half = 1.5f;              // orthographic xmag = ymag
  bool triangle = false;               // a triangle emitter: the square's half (-a,-a) (a,-a) (a,a)
  bool turned_away = false;            // the one-sided emitter faces up, away from the floor:
                                       // nothing lights the floor, every pixel is 0
};

// builtin:floor_small_light and builtin:floor_large_light: FloorLightScene with the
// emitter's half-size set to these, its radiance scaled to keep the power.
constexpr float kSmallLightHalf = 0.1f;
constexpr float kLargeLightHalf = 2.0f;

// builtin:point_floor — the floor of FloorLightScene under a point light of intensity I
// at the emitter's height: radiance albedo I cos(theta) / (pi d^2). Only stages 4 and 5
// see it. builtin:spot_floor — the same with a spot light pointing straight down: times
// its falloff (common/kernel/punctual_light.glsl spot_falloff).
// builtin:sun_floor — the floor under a directional light of irradiance E at angle theta
// from the vertical: albedo E cos(theta) / pi everywhere.
struct PointFloorScene {
  FloorLightScene floor;
  uint kind = kPunctualPoint;             // kPunctual*
  glm::vec3 intensity{2.0f, 2.0f, 2.0f};  // W/sr; W/m^2 for the directional light
  // A spot light's cone angles (radians): the outer cone holds the whole view (whose
  // corners are 1.13 rad off the axis), since a pixel that the falloff's last sliver
  // only grazes is lit by a few rare samples and its variance misjudged; the kernel test
  // (test_light_sampling.cpp) checks the dark beyond the outer cone.
  float inner = 0.4f, outer = 1.2f;
  float sun_angle = 0.6435011f;           // a directional light's angle from the vertical (cos 0.8)
};
// The falloff of a spot light with these cone angles at angle theta from its axis, in double:
// what spot_falloff computes, for the tests' closed forms.
double spot_falloff(double inner, double outer, double theta);

// builtin:point_in_sphere — the inside of a diffuse sphere (radius 1, albedo 0.5) lit by a
// point light of intensity pi at its centre, seen from the centre: every pixel is
// albedo I / (pi r^2) / (1 - albedo) = 1 (pbrt's analytic test scene). Only stage4 sees it.
struct PointInSphereScene {
  float radius = 1.0f;
  float albedo = 0.5f;
  float intensity = 3.14159265f;
};

// builtin:mirror — a mirror facing an orthographic camera reflects an emitter behind the
// camera straight back: every pixel is F0 x Le (Schlick's Fresnel at normal incidence).
struct MirrorScene {
  glm::vec3 f0{0.9f, 0.6f, 0.3f};
  glm::vec3 emission{1.0f, 2.0f, 3.0f};
  float emitter_z = 6.0f, camera_z = 5.0f;  // mirror at z = 0, facing +z
};

// builtin:glass_slab — a glass slab of index `ior` between an orthographic camera and a
// uniform emitter: every pixel is Le times the slab's transmittance with all its internal
// reflections, (1 - R) / (1 + R), R = ((ior - 1) / (ior + 1))^2.
struct GlassSlabScene {
  float ior = 1.5f;
  float half_thickness = 0.5f;  // the slab spans z in [-t, t], x, y in [-3, 3]
  float emission = 1.0f;        // emitter at z = -3, facing +z
  float camera_z = 5.0f;
};


// The scenes themselves, for tests that vary a parameter (builtin:NAME uses the defaults).
Scene make_floor_light(const FloorLightScene& a);
Scene make_mirror(const MirrorScene& a);
Scene make_glass_slab(const GlassSlabScene& a);
Scene make_furnace(const FurnaceScene& a);
Scene make_furnace_sphere(const FurnaceSphereScene& a);
Scene make_furnace_mesh(const FurnaceMeshScene& a);
Scene make_sphere(const SphereScene& a);
Scene make_point_floor(const PointFloorScene& a);
Scene make_point_in_sphere(const PointInSphereScene& a);
Scene make_quad(const QuadScene& a);

}  // namespace pt::analytic
