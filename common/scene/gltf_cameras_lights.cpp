// The glTF loader's cameras and KHR_lights_punctual lights (gltf_scene_builder.h), for the
// loader of the contract (README.md) "Scenes": every camera of the default scene as a
// CameraDesc (the first is the scene's), and point, spot and directional lights as the
// scene's punctual lights. The cameras place stage1's camera rays (the article's
// raycasting, Eq. (2)); the punctual lights, deltas the article does not have, only
// stage4 and stage5 see (docs/stage4_direct_indirect.md).
#include <cmath>
#include <cstdio>
#include <string>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include "common/base/error.h"
#include "common/scene/gltf_scene_builder.h"
#include "common/scene/gltf_validate.h"

namespace pt::gltf {

void SceneBuilder::add_camera(int index, const glm::dmat4& world, const tinygltf::Node& node,
                              const std::string& where) {
  for (const SceneCamera& c : scene_.cameras) {
    if (c.index == index) return;
  }
  const tinygltf::Camera& c = model_.cameras[index];
  std::string what = "cameras[" + std::to_string(index) + "]";
  CameraDesc desc;
  desc.to_world = glm::mat4(world);
  if (c.type == "perspective") {
    desc.kind = kCameraPerspective;
    desc.yfov = checked_float(file_, c.perspective.yfov, what + ".perspective.yfov", 1e-6, 3.14159);
    if (c.perspective.aspectRatio != 0.0)
      desc.aspect_ratio = checked_float(file_, c.perspective.aspectRatio, what + ".perspective.aspectRatio", 1e-6, 1e6);
  } else if (c.type == "orthographic") {
    desc.kind = kCameraOrthographic;
    desc.xmag = checked_float(file_, c.orthographic.xmag, what + ".orthographic.xmag");
    desc.ymag = checked_float(file_, c.orthographic.ymag, what + ".orthographic.ymag");
    if (desc.xmag == 0.0f || desc.ymag == 0.0f)
      fail(file_, what + ": xmag and ymag must not be zero; re-export it");
  } else {
    fail(file_,
         what + ".type '" + c.type + "' is neither perspective nor orthographic: " + gltf::kReexport);
  }
  if (!scene_.camera) scene_.camera = desc;
  scene_.cameras.push_back(SceneCamera{desc, index, c.name, node.name.empty() ? where : node.name});
}

namespace {

// KHR_lights_punctual gives intensities in photometric units: candela (lm/sr) for point and
// spot lights, lux (lm/m^2) for directional ones. The renderer's radiance is radiometric
// (the scene's own units, W), so they are divided by 683 lm/W, the luminous efficacy of
// 555 nm light, as Blender's glTF importer does in its default "Standard" lighting mode:
// I / 683 W/sr and E / 683 W/m^2. Built-in scenes give theirs in W directly.
constexpr double kLumensPerWatt = 683.0;

// The file's lights of the types modelled (for the note on stderr).
std::size_t modelled_lights(const tinygltf::Model& model) {
  std::size_t n = 0;
  for (const tinygltf::Light& l : model.lights) n += l.type == "point" || l.type == "spot" || l.type == "directional";
  return n;
}

}  // namespace

void SceneBuilder::add_light(int index, const glm::dmat4& world) {
  const tinygltf::Light& light = model_.lights[index];
  std::string where = "extensions.KHR_lights_punctual.lights[" + std::to_string(index) + "]";
  PointLight out{};
  if (light.type == "point") {
    out.kind = kPunctualPoint;
  } else if (light.type == "spot") {
    out.kind = kPunctualSpot;
    const double half_pi = 1.5707963267948966;
    float inner = checked_float(file_, light.spot.innerConeAngle, where + ".spot.innerConeAngle", 0.0, half_pi);
    float outer = checked_float(file_, light.spot.outerConeAngle, where + ".spot.outerConeAngle", 0.0, half_pi);
    // Blender writes inner == outer for a spot of Spot Blend 0: a hard-edged cone, full up
    // to the outer angle and dark beyond. An inner cone at or past the outer one means the
    // same; it is made equal to it, which spot_falloff (punctual_light.glsl) takes as a step
    // and the light table's power (scene_lights.cpp) as the cone's 2 pi (1 - cos outer).
    if (!(inner < outer)) inner = outer;
    out.cos_inner = std::cos(inner), out.cos_outer = std::cos(outer);
  } else if (light.type == "directional") {
    out.kind = kPunctualDirectional;
  } else {
    warn_once(file_ + ": scene has lights of type \"" + light.type +
              "\" (KHR_lights_punctual); only point, spot and directional lights are modelled");
    return;
  }
  float intensity = checked_float(file_, light.intensity, where + ".intensity", 0.0);
  glm::vec3 color(1.0f);
  if (!light.color.empty() && light.color.size() != 3)
    fail(file_, where + ".color needs 3 numbers: " + gltf::kReexport);
  for (std::size_t k = 0; k < light.color.size(); ++k) {
    color[int(k)] = checked_float(file_, light.color[k], where + ".color[" + std::to_string(k) + "]", 0.0);
  }
  // Candela to W/sr, lux to W/m^2; then the colour (linear), as the extension multiplies.
  out.intensity = float(double(intensity) / kLumensPerWatt) * color;
  if (!std::isfinite(out.intensity.x + out.intensity.y + out.intensity.z))
    fail(file_, where + ": intensity x color overflows: " + gltf::kReexport);
  if (light.range > 0.0 && out.kind != kPunctualDirectional)
    warn_once(file_ + ": scene has lights with a range; it is ignored (light falls off as 1 / d^2 to any distance)");
  out.position = glm::vec3(world[3]);
  if (out.kind != kPunctualPoint) {
    glm::dvec3 axis = -glm::dvec3(world[2]);  // the node's -Z in the world
    double length = glm::length(axis);
    if (!(length > 0.0) || !std::isfinite(length)) {
      warn_once(file_ + ": a " + light.type + " light's node is scaled to nothing; the light is skipped");
      return;
    }
    out.direction = glm::vec3(axis / length);
  }
  // Said once per file read, where its first light is placed: the units a user must know
  // to compare the image with another renderer's.
  if (scene_.point_lights.empty()) {
    std::size_t n = modelled_lights(model_);
    std::fprintf(stderr, "%s: %zu KHR_lights_punctual light%s: photometric units (cd, lux) converted at %g lm/W\n",
                 file_.c_str(), n, n == 1 ? "" : "s", kLumensPerWatt);
  }
  scene_.point_lights.push_back(out);
}

}  // namespace pt::gltf
