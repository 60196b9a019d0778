// Whole-scene checks of a loaded glTF scene (scene_sanity.h): the triangle budget before the
// node tree is expanded, then degenerate cameras and scenes too large or too small for 32-bit
// floats. Not part of the article: machinery that says in one line why an image would be black.
#include "common/scene/scene_sanity.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>

#include <glm/glm.hpp>

#include "common/base/error.h"
#include "common/scene/bvh.h"

namespace pt {

namespace {

std::atomic<std::uint64_t> memory_budget{0};

std::string gigabytes(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f GB", bytes / 1e9);
  return text;
}

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", v);
  return text;
}

[[noreturn]] void refuse(const std::string& file, const std::string& message) {
  throw Error(kExitBadScene, file + ": " + message);
}

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// The camera's frame as make_camera (scene_camera.cpp) builds it in float: finite, or the
// camera sees nothing (every ray NaN, a black image).
bool camera_frame_is_finite(const CameraDesc& desc) {
  const glm::vec3 origin(desc.to_world[3]);
  const glm::vec3 forward = glm::normalize(-glm::vec3(desc.to_world[2]));
  const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(desc.to_world[1])));
  return finite(origin) && finite(forward) && finite(right) && finite(glm::cross(right, forward));
}

std::string camera_name(const SceneCamera& c) {
  std::string name = "cameras[" + std::to_string(c.index) + "]";
  if (!c.name.empty()) name += " '" + c.name.substr(0, 60) + "'";
  return name + " (placed by " + (c.node.rfind("nodes[", 0) == 0 ? c.node : "node '" + c.node.substr(0, 60) + "'") +
         ")";
}

}  // namespace

void set_scene_memory_budget(std::uint64_t bytes) { memory_budget = bytes; }

void check_triangle_budget(std::uint64_t triangles, bool overflowed, bool attributes, const std::string& file,
                           bool shading) {
  const std::uint64_t per_triangle = kSceneBytesPerTriangle + (attributes ? kAttributeBytesPerTriangle : 0) +
                                     (shading ? sizeof(TriangleShading) : 0);
  std::uint64_t bytes = 0;
  overflowed = overflowed || __builtin_mul_overflow(triangles, per_triangle, &bytes);
  if (overflowed || triangles > kBvhMaxTriangles) {
    refuse(file, "its nodes place " + (overflowed ? std::string("more than 2^64") : std::to_string(triangles)) +
                     " triangles (a mesh counts once for every node and every EXT_mesh_gpu_instancing instance that "
                     "places it), more than the " +
                     std::to_string(kBvhMaxTriangles) + " the BVH takes: place fewer copies or use coarser meshes");
  }
  const std::uint64_t budget = memory_budget;
  if (budget != 0 && bytes > budget) {
    refuse(file, "its nodes place " + std::to_string(triangles) + " triangles (a mesh counts once for every node "
                 "and every EXT_mesh_gpu_instancing instance that places it), which need " + gigabytes(double(bytes)) + " of memory at " +
                 std::to_string(per_triangle) + " bytes each; this machine has " + gigabytes(double(budget)) +
                 " available: place fewer copies, use coarser meshes or a machine with more memory");
  }
}

void check_scene_sanity(const Scene& scene, const std::string& file) {
  // Extent first (the geometry's bounding box and the cameras' positions, in double): a scene
  // scaled beyond float's reach, cameras and all, is said as such.
  const Bounds b = scene.bounds();
  double largest = 0.0, extent = 0.0;
  for (int k = 0; k < 3 && !b.empty(); ++k) {
    largest = std::max({largest, std::abs(double(b.lo[k])), std::abs(double(b.hi[k]))});
    extent = std::max(extent, double(b.hi[k]) - double(b.lo[k]));
  }
  double camera_largest = 0.0;
  for (const SceneCamera& c : scene.cameras) {
    for (int k = 0; k < 3; ++k) camera_largest = std::max(camera_largest, std::abs(double(c.desc.to_world[3][k])));
  }
  if (std::max(largest, camera_largest) > kMaxSceneCoordinate) {
    refuse(file, "its " + std::string(camera_largest > largest ? "cameras reach" : "geometry reaches") +
                     " coordinates of " + number(std::max(largest, camera_largest)) + ", beyond the " +
                     number(kMaxSceneCoordinate) + " that 32-bit floats resolve in the ray tests (their products "
                     "would overflow and the image be black): scale the scene down (e.g. a root node's scale)");
  }
  if (extent > kMaxSceneExtent) {
    refuse(file, "its geometry is " + number(extent) + " across, beyond the " + number(kMaxSceneExtent) +
                     " that 32-bit floats resolve in the shading normals (edge^4 would overflow and the image be "
                     "black): scale the scene down (e.g. a root node's scale)");
  }
  if (!b.empty() && extent < kMinSceneExtent) {
    refuse(file, "its geometry is " + number(extent) + " across, below the " + number(kMinSceneExtent) +
                     " that 32-bit floats resolve in the shading normals (edge^4 would vanish and the image be "
                     "black): scale the scene up (e.g. a root node's scale)");
  }
  if (!b.empty() && extent < kMinRelativeExtent * largest) {
    warn_once(file + ": its geometry is " + number(extent) + " across but lies " + number(largest) +
              " from the origin, where 32-bit floats space coordinates " + number(largest * 0x1p-23) +
              " apart: shapes will look jagged or be missed; move the scene to the origin");
  }
  // Cameras: make_camera normalises the node's -Z and +Y axes; scale 0 leaves nothing to normalise.
  for (const SceneCamera& c : scene.cameras) {
    if (!camera_frame_is_finite(c.desc)) {
      refuse(file, camera_name(c) + " has a degenerate transform, so it sees nothing: its world scale is 0 or too "
                   "far from 1 for 32-bit floats to normalise its axes, or not finite, or its view and up axes are "
                   "parallel; give the camera's node a scale near 1");
    }
  }
}

}  // namespace pt
