// The glTF loader's walk of the default scene (gltf_loader.cpp), which fills a pt::Scene:
// nodes, meshes and materials in gltf_loader.cpp, a primitive's triangles in gltf_triangles.cpp,
// cameras and KHR_lights_punctual lights in gltf_cameras_lights.cpp. Internal to the loader; not part of the article: how a file
// becomes the scene (the contract (README.md) "Scenes").
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include "common/scene/gltf_textures.h"
#include "common/scene/scene.h"

namespace pt::gltf {

// What the chosen scene draws, counted before any triangle is made (gltf_primitives.cpp): each
// primitive of mode 4, 5 or 6 with POSITION gives its triangles (mode_triangles of its indices'
// count, else POSITION's), once for every node that places its mesh and, on a node with
// EXT_mesh_gpu_instancing, once for every instance. check_model has made the nodes a tree (each
// visited once) and every index valid. attributes: some primitive will need TriangleAttributes
// (a texture, an alpha mask or COLOR_0), which SceneBuilder::take then keeps for every triangle.
// skipped: the primitives of modes 0-3 (points, lines, line loops, line strips), each counted once.
struct DrawCount {
  std::uint64_t triangles = 0;
  bool overflowed = false;
  bool attributes = false;
  bool shading = false;  // some primitive will need TriangleShading (NORMAL or a normal map)
  std::uint64_t skipped[4] = {0, 0, 0, 0};
};
DrawCount count_draws(const tinygltf::Model& model, const std::vector<int>& roots);

// "3 primitives of mode LINES skipped (points and lines are not drawn)", or "" when none was.
std::string skipped_text(const DrawCount& count);

// "POINTS", "LINES", ..., "TRIANGLE_FAN" for glTF's modes 0-6.
const char* mode_name(int mode);

// The triangles `entries` indices (or vertices) of a primitive of `mode` make: n / 3 for lists,
// n - 2 for strips and fans (from 3 entries), 0 for points and lines.
std::uint64_t mode_triangles(int mode, std::uint64_t entries);

// A primitive's indices as a triangle list, three a triangle, in the glTF specification's order:
// strips alternate so that every triangle keeps the first one's winding (its front face), fans
// share the first vertex. Triangles of a strip or fan that name a vertex twice (joins) are left out.
std::vector<std::uint32_t> triangulate(int mode, const std::vector<std::uint32_t>& entries);

// How many times a node places its mesh: its EXT_mesh_gpu_instancing accessors' count (checked
// equal by check_model), else 1.
std::uint64_t instance_count(const tinygltf::Model& model, const tinygltf::Node& node);

// Each instance's transform in the node's space (translation * rotation * scale, each optional),
// so that an instance's world transform is node_world * instance; one identity without the extension.
std::vector<glm::dmat4> instance_transforms(const tinygltf::Model& model, int node_index, const std::string& file);

// The roots of the scene drawn: --gltf-scene's choice (`request`: its index or name; none there
// throws pt::Error(kExitBadOption) naming the scenes there are), else the file's `scene`, else
// scene 0, saying on stderr which when the file has several; every root node when it has none.
std::vector<int> choose_scene(const tinygltf::Model& model, const std::vector<int>& parents, const std::string& request,
                              const std::string& file);

// A primitive's NORMAL and TANGENT (gltf_shading.cpp), in the mesh's space; each empty when
// the file has none. Either is VEC3 / VEC4 of FLOAT with one entry a vertex.
struct PrimitiveShading {
  std::vector<glm::vec3> normals;
  std::vector<glm::vec4> tangents;  // xyz and the handedness w (+1 or -1)
};
PrimitiveShading read_shading(const tinygltf::Model& model, const tinygltf::Primitive& prim, std::size_t vertex_count,
                              const std::string& file, const std::string& where);

// A triangle's tangent made from its UVs (p: world corners, the tangent dP/du made orthogonal
// to face_normal, the handedness that makes handedness * cross(n, t) run along -dP/dv); with
// no UV area, any tangent orthogonal to the face normal. Normals: the face normal.
TriangleShading tangents_from_uvs(const glm::vec3 p[3], const glm::vec2 uv[3], glm::vec3 face_normal);

// Per-vertex tangents (xyz, handedness w) of a primitive with normals and no TANGENT, made as
// MikkTSpace makes them in essence (gltf_tangents.cpp): each triangle's dP/du, in the tangent
// plane of each corner's normal, weighted by the corner's angle and summed over the vertices
// that share position, normal and uv and the triangles whose UVs run the same way round; then
// made orthogonal to the normal. A vertex no triangle with UV area touches gets (0, 0, 0, 0).
std::vector<glm::vec4> vertex_tangents(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals,
                                       const std::vector<glm::vec2>& uv, const std::vector<std::uint32_t>& indices);

// The shading frame of the triangle of vertices `corner` (p: its world corners, uv: its
// TEXCOORD_0) in world space: the primitive's normals by the inverse transpose of `world`
// (turned to the front face), its tangents by `world` or made from the UVs. Returns whether
// the triangle needs it: a vertex normal away from the face normal, or a normal map. A zero
// tangent in prim.tangents is replaced by the one made from the UVs.
bool shade_triangle(const PrimitiveShading& prim, const std::uint32_t corner[3], const glm::vec3 p[3],
                    const glm::vec2 uv[3], const glm::dmat4& world, bool normal_mapped, TriangleShading& out);

// Walks the chosen scene and fills a pt::Scene.
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
  // directional light shining along the node's -Z. The extension's photometric units are
  // converted at 683 lm/W: candela to W/sr (point, spot), lux to W/m^2 (directional).
  void add_light(int index, const glm::dmat4& world);

  // A mesh placed once for each of `worlds` (a node's EXT_mesh_gpu_instancing instances);
  // triangle lists, strips and fans (gltf_primitives.cpp: triangulate), points and lines skipped.
  void add_mesh(int mesh_index, const std::vector<glm::dmat4>& worlds);
  void add_primitive(const tinygltf::Primitive& prim, int position_accessor, const std::string& where,
                     const std::vector<glm::dmat4>& worlds);
  // A primitive's triangles (indices three a triangle) placed by `world`, with TEXCOORD_0
  // (uv), TEXCOORD_1 (uv_set1) and COLOR_0 where not empty; those without area skipped.
  void add_triangles(const std::vector<std::uint32_t>& indices, const std::vector<glm::vec3>& positions,
                     const glm::dmat4& world, uint material, const std::vector<glm::vec2>& uv,
                     const std::vector<glm::vec2>& uv_set1, const std::vector<glm::vec4>& colors,
                     const PrimitiveShading& shading);

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
  std::vector<TriangleShading> shading_;             // parallel to scene_.triangles once needed
  bool shading_on_ = false;                          // a primitive has NORMAL or a normal map
};

}  // namespace pt::gltf
