// The glTF loader's walk of the default scene (gltf_loader.cpp), which fills a pt::Scene:
// nodes, meshes and materials in gltf_loader.cpp, cameras and KHR_lights_punctual lights in
// gltf_cameras_lights.cpp. Internal to the loader; not part of the article: how a file
// becomes the scene (the contract (README.md) "Scenes").
#pragma once

#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include "common/scene/gltf_textures.h"
#include "common/scene/scene.h"

namespace pt::gltf {

// Walks the default scene and fills a pt::Scene.
class SceneBuilder {
 public:
  SceneBuilder(const tinygltf::Model& model, const std::string& file)
      : model_(model), file_(file), textures_(model, file) {
    scene_.name = file;
  }

  // Depth first, children in order, with an explicit stack (hierarchies can be deep).
  void add_tree(int root);

  // The scene; textures and vertex colours when a drawn triangle has them (both arrays
  // then parallel to materials and triangles), their images decoded now.
  Scene take();

 private:
  void add_node(int index, const tinygltf::Node& node, const glm::dmat4& world);

  // Every camera of the default scene, in the order met (a camera that several nodes place:
  // at the first); the first is the scene's camera until --camera picks another.
  void add_camera(int index, const glm::dmat4& world, const tinygltf::Node& node, const std::string& where);

  // A KHR_lights_punctual light on a node: a point light at the node's origin, a spot or
  // directional light shining along the node's -Z. Units are taken as radiometric: the
  // intensity as W/sr (point, spot) or W/m^2 (directional), as the renderer's other lights.
  void add_light(int index, const glm::dmat4& world);

  void add_mesh(int mesh_index, const glm::dmat4& world);
  void add_primitive(const tinygltf::Primitive& prim, int position_accessor, const std::string& where,
                     const glm::dmat4& world);

  // Each glTF material used is added once; -1 is glTF's default material.
  uint material_index(int gltf_index);

  const tinygltf::Model& model_;
  std::string file_;
  Scene scene_;
  std::map<int, uint> materials_;  // glTF material index -> Scene::materials index
  gltf::TextureBuilder textures_;   // the textures the materials read
  std::vector<MaterialTextures> material_textures_;  // parallel to scene_.materials
  std::vector<TriangleAttributes> attributes_;       // parallel to scene_.triangles once needed
  bool attributes_on_ = false;                       // a triangle has needed them
};

}  // namespace pt::gltf
