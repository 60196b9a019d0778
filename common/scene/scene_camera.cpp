// The camera (scene.h): the kernel camera of an image's aspect (make_camera), the framing
// of a scene without a camera (frame_bounds), --camera (select_camera) and the orthographic
// cameras of the built-in scenes. Its rays are stage1's camera rays (the article's
// raycasting, Eq. (2); common/kernel/camera.glsl), which every stage shares.
#include "common/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "common/base/error.h"

namespace pt {

// A camera on `position` looking straight down (-y), image up = -z.
CameraDesc orthographic_down(glm::vec3 position, float half) {
  CameraDesc cam;
  cam.kind = kCameraOrthographic;
  cam.xmag = half, cam.ymag = half;
  cam.to_world = glm::mat4(glm::vec4(1, 0, 0, 0), glm::vec4(0, 0, -1, 0), glm::vec4(0, 1, 0, 0), glm::vec4(position, 1));
  return cam;
}

// An orthographic camera on the +z axis looking down -z.
CameraDesc orthographic_front(float z, float half) {
  CameraDesc cam;
  cam.kind = kCameraOrthographic;
  cam.xmag = half, cam.ymag = half;
  cam.to_world = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, z));
  return cam;
}

CameraDesc frame_bounds(const Bounds& bounds, float aspect) {
  CameraDesc desc;  // perspective, the default yfov
  Bounds b = bounds;
  if (b.empty()) b.lo = glm::vec3(-1.0f), b.hi = glm::vec3(1.0f);
  const double azimuth = M_PI / 4.0, elevation = M_PI / 6.0;
  // The camera's frame: it looks along -back, towards the centre, with image up near +Y.
  const glm::dvec3 back(std::sin(azimuth) * std::cos(elevation), std::sin(elevation),
                        std::cos(azimuth) * std::cos(elevation));
  const glm::dvec3 right = glm::normalize(glm::cross(glm::dvec3(0.0, 1.0, 0.0), back));
  const glm::dvec3 up = glm::cross(back, right);
  const glm::dvec3 center = 0.5 * (glm::dvec3(b.lo) + glm::dvec3(b.hi));
  // A corner at (x, y) across and z towards the camera from the centre, seen from distance
  // D along `back`, is in the picture when |x| <= tx (D - z) and |y| <= ty (D - z).
  const double ty = std::tan(0.5 * double(desc.yfov)), tx = ty * double(aspect);
  const double margin = 1.05;
  double distance = 0.0, depth = 0.0;
  for (int corner = 0; corner < 8; corner++) {
    glm::dvec3 p((corner & 1) ? b.hi.x : b.lo.x, (corner & 2) ? b.hi.y : b.lo.y, (corner & 4) ? b.hi.z : b.lo.z);
    glm::dvec3 o = p - center;
    double z = glm::dot(o, back);
    distance = std::max({distance, margin * std::abs(glm::dot(o, right)) / tx + z,
                         margin * std::abs(glm::dot(o, up)) / ty + z});
    depth = std::max(depth, z);
  }
  // The nearest corner stays in front of the camera (a flat scene seen edge-on has none).
  distance = std::max({distance, depth * 1.01, 1e-6 * std::max(1.0, glm::length(center))});
  glm::dmat4 to_world(1.0);
  to_world[0] = glm::dvec4(right, 0.0), to_world[1] = glm::dvec4(up, 0.0), to_world[2] = glm::dvec4(back, 0.0);
  to_world[3] = glm::dvec4(center + distance * back, 1.0);
  desc.to_world = glm::mat4(to_world);
  return desc;
}

void select_camera(Scene& scene, const std::string& request) {
  std::string there;  // the cameras there are, for the message
  for (const SceneCamera& c : scene.cameras) {
    bool by_index = !request.empty() && request.find_first_not_of("0123456789") == std::string::npos &&
                    request.size() < 10 && std::stoi(request) == c.index;
    if (by_index || (!c.name.empty() && c.name == request) || c.node == request) {
      scene.camera = c.desc;
      return;
    }
    there += (there.empty() ? "" : ", ") + std::to_string(c.index) + (c.name.empty() ? "" : " '" + c.name + "'") +
             " (node '" + c.node + "')";
  }
  if (scene.cameras.empty()) {
    throw Error(kExitBadOption, "--camera " + request + ": " + scene.name +
                                    " has no cameras of its own to choose from; leave --camera out");
  }
  throw Error(kExitBadOption, "--camera " + request + ": " + scene.name + " has no such camera; its cameras: " +
                                  there + " (give the index or a name)");
}

Camera make_camera(const Scene& scene, float aspect) {
  CameraDesc desc = scene.camera ? *scene.camera : frame_bounds(scene.bounds(), aspect);
  glm::vec3 origin(desc.to_world[3]);
  glm::vec3 forward = glm::normalize(-glm::vec3(desc.to_world[2]));
  glm::vec3 up0 = glm::vec3(desc.to_world[1]);
  glm::vec3 right = glm::normalize(glm::cross(forward, up0));
  glm::vec3 up = glm::cross(right, forward);

  Camera c{};
  c.origin = origin;
  c.forward = forward;
  c.right = right;
  c.up = up;
  if (desc.kind == kCameraOrthographic) {
    c.extent_x = desc.xmag, c.extent_y = desc.ymag;
  } else {
    float t = std::tan(0.5f * desc.yfov);
    c.extent_x = t * aspect, c.extent_y = t;
  }
  c.kind = desc.kind;
  c.clip_start = desc.clip_start;
  return c;
}

}  // namespace pt
