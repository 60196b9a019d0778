// The glTF 2.0 loader of the contract (README.md) "Scenes": every triangle primitive of the chosen
// scene (which, and what it draws: gltf_primitives.cpp; a primitive's triangles and their
// attributes: gltf_triangles.cpp) with node transforms and instances applied,
// metallic-roughness factors as materials (gltf_materials.cpp),
// KHR_lights_punctual point lights and the first camera (both gltf_cameras_lights.cpp). Checks of
// the file itself live behind gltf_validate.h; what is not modelled is named once on stderr.
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <tiny_gltf.h>

#include "common/base/error.h"
#include "common/scene/gltf_materials.h"
#include "common/scene/gltf_precheck_uris.h"
#include "common/scene/gltf_scene_builder.h"
#include "common/scene/gltf_textures.h"
#include "common/scene/gltf_validate.h"
#include "common/scene/scene_loading.h"
#include "common/scene/scene_sanity.h"

namespace pt {

namespace {

using gltf::fail;

tinygltf::Model parse_model(gltf::SourceFile& source, const std::string& path) {
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&gltf::keep_image_bytes, nullptr);  // OpenImageIO decodes them (gltf_images.cpp)
  gltf::detail::SceneFolder folder{source.base_dir, gltf::detail::scene_root(source.base_dir), path};
  loader.SetFsCallbacks(gltf::detail::scene_folder_callbacks(&folder));
  tinygltf::Model model;
  std::string err, warn;  // tinygltf's warnings concern images, which are not used
  unsigned size = unsigned(source.bytes.size());
  bool ok = source.binary
                ? loader.LoadBinaryFromMemory(&model, &err, &warn, source.bytes.data(), size, source.base_dir)
                : loader.LoadASCIIFromString(&model, &err, &warn,
                                             reinterpret_cast<const char*>(source.bytes.data()), size,
                                             source.base_dir);
  if (!ok) {
    // What the prechecks leave to tinygltf are violations of the specification (a required
    // property missing, one of the wrong type), which its first line names.
    std::string first = err.substr(0, err.find('\n'));
    while (!first.empty() && (first.back() == '.' || first.back() == ' ')) first.pop_back();
    if (first.size() > 200) first = first.substr(0, 200) + "...";
    fail(path, "the glTF library (tinygltf) cannot read it: " +
                   (first.empty() ? std::string("it gives no reason") : first) + "; " + gltf::kReexport);
  }
  return model;
}

// A node's own transform: its matrix, else translation * rotation * scale.
glm::dmat4 local_transform(const tinygltf::Node& node) {
  if (node.matrix.size() == 16) return glm::make_mat4(node.matrix.data());
  glm::dmat4 m(1.0);
  if (node.translation.size() == 3) m = glm::translate(m, glm::make_vec3(node.translation.data()));
  if (node.rotation.size() == 4) {
    const std::vector<double>& q = node.rotation;  // glTF order: x, y, z, w
    m = m * glm::mat4_cast(glm::normalize(glm::dquat(q[3], q[0], q[1], q[2])));
  }
  if (node.scale.size() == 3) m = glm::scale(m, glm::make_vec3(node.scale.data()));
  return m;
}

void warn_unmodelled(const tinygltf::Model& model, const std::string& file) {
  if (!model.animations.empty())
    warn_once(file + ": scene has animations; they are not modelled (drawn at rest)");
  if (!model.skins.empty()) warn_once(file + ": scene has skins; they are not modelled (drawn in bind pose)");
}

bool all_finite(const glm::dmat4& m) {
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) {
      if (!std::isfinite(float(m[c][r]))) return false;
    }
  }
  return true;
}

}  // namespace

namespace gltf {

void SceneBuilder::add_tree(int root) {
  std::vector<std::pair<int, glm::dmat4>> stack = {{root, glm::dmat4(1.0)}};
  while (!stack.empty()) {
    auto [index, parent_world] = stack.back();
    stack.pop_back();
    const tinygltf::Node& node = model_.nodes[index];
    glm::dmat4 world = parent_world * local_transform(node);
    add_node(index, node, world);
    for (auto child = node.children.rbegin(); child != node.children.rend(); ++child) {
      stack.emplace_back(*child, world);
    }
  }
}

Scene SceneBuilder::take() {
  if (attributes_on_) {
    attributes_.resize(scene_.triangles.size(), no_triangle_attributes());
    scene_.triangle_attributes = std::move(attributes_);
    scene_.material_textures = material_textures_;
    textures_.decode_into(scene_);
    mark_alpha_masked(scene_);
  }
  // Shading normals only where some triangle needs them (kFeatureShadingNormals).
  bool any = false;
  for (const Triangle& t : scene_.triangles) any = any || (t.flags & kTriangleShadingNormals);
  if (shading_on_ && any) scene_.triangle_shading = std::move(shading_);
  return std::move(scene_);
}

void SceneBuilder::add_node(int index, const tinygltf::Node& node, const glm::dmat4& world) {
  std::string where = "nodes[" + std::to_string(index) + "]";
  if (!all_finite(world))
    fail(file_, where + ": its world transform overflows 32-bit floats: " + gltf::kReexport);
  if (node.camera != -1) add_camera(node.camera, world, node, where);
  if (node.mesh != -1) {
    std::vector<glm::dmat4> worlds = gltf::instance_transforms(model_, index, file_);
    for (glm::dmat4& w : worlds) {
      w = world * w;  // an instance's TRS is in the node's space
      if (!all_finite(w))
        fail(file_, where + ": an EXT_mesh_gpu_instancing instance's world transform overflows 32-bit floats: " +
                        gltf::kReexport);
    }
    add_mesh(node.mesh, worlds);
  }
  auto light = node.extensions.find("KHR_lights_punctual");
  if (light != node.extensions.end()) add_light(light->second.Get("light").GetNumberAsInt(), world);
}

void SceneBuilder::add_mesh(int mesh_index, const std::vector<glm::dmat4>& worlds) {
  const tinygltf::Mesh& mesh = model_.meshes[mesh_index];
  for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
    const tinygltf::Primitive& prim = mesh.primitives[p];
    std::string where = "meshes[" + std::to_string(mesh_index) + "].primitives[" + std::to_string(p) + "]";
    if (!prim.targets.empty())
      warn_once(file_ + ": scene has morph targets; they are not modelled (base shape)");
    if (prim.mode < TINYGLTF_MODE_TRIANGLES) continue;  // points and lines: counted by count_draws
    auto position = prim.attributes.find("POSITION");
    if (position == prim.attributes.end()) {
      warn_once(file_ + ": " + where + " has no POSITION; it is skipped");
      continue;
    }
    add_primitive(prim, position->second, where, worlds);
  }
}

uint SceneBuilder::material_index(int gltf_index) {
  auto found = materials_.find(gltf_index);
  if (found != materials_.end()) return found->second;
  Material m = gltf_index == -1
                   ? make_gltf_material(glm::vec3(1.0f), 1.0f, 1.0f, 0.0f, 1.5f, glm::vec3(0.0f), false)
                   : gltf::convert_material(model_, gltf_index, file_);
  // Its textures (noted now, decoded by take() if a drawn triangle uses them).
  material_textures_.push_back(gltf_index == -1 ? no_material_textures()
                                                : textures_.material_textures(gltf_index, m));
  return materials_[gltf_index] = scene_.add_material(m);
}

}  // namespace gltf

Scene load_gltf(const std::string& path, const std::string& scene_choice) {
  gltf::SourceFile source = gltf::read_and_precheck(path);
  tinygltf::Model model = parse_model(source, path);
  std::vector<int> parents = gltf::check_model(model, path);
  const std::vector<int> roots = gltf::choose_scene(model, parents, scene_choice, path);
  warn_unmodelled(model, path);
  const gltf::DrawCount count = gltf::count_draws(model, roots);
  const std::string skipped = gltf::skipped_text(count);
  check_triangle_budget(count.triangles, count.overflowed, count.attributes, path, count.shading);
  gltf::SceneBuilder builder(model, path);
  for (int root : roots) builder.add_tree(root);
  Scene scene = builder.take();
  if (scene.triangles.empty()) {
    std::string why = skipped.empty() ? "" : skipped;
    if (scene.degenerate_triangles > 0) {
      why += (why.empty() ? "" : "; ") + std::to_string(scene.degenerate_triangles) +
             " triangle(s) without area (zero or non-finite) skipped";
    }
    if (why.empty()) why = "the scene drawn places no mesh with triangles (modes 4, 5, 6)";
    throw Error(kExitBadScene, path + ": no triangles to draw: " + why);
  }
  if (!skipped.empty()) warn_once(path + ": " + skipped);
  if (scene.degenerate_triangles > 0) {
    warn_once(path + ": " + std::to_string(scene.degenerate_triangles) +
              " degenerate triangle(s) (zero area or non-finite) skipped");
  }
  check_scene_sanity(scene, path);
  return scene;
}

}  // namespace pt
