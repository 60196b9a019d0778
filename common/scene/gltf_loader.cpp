// The glTF 2.0 loader of the contract (README.md) "Scenes": every triangle primitive of the chosen
// scene (which, and what it draws: gltf_primitives.cpp) with node transforms and instances applied,
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

void SceneBuilder::add_primitive(const tinygltf::Primitive& prim, int position_accessor, const std::string& where,
                                 const std::vector<glm::dmat4>& worlds) {
  std::string what = "accessors[" + std::to_string(position_accessor) + "] (POSITION of " + where + ")";
  std::vector<glm::vec3> positions = gltf::read_positions(model_, position_accessor, file_, what);
  std::vector<std::uint32_t> indices;
  if (prim.indices != -1) {
    what = "accessors[" + std::to_string(prim.indices) + "] (indices of " + where + ")";
    indices = gltf::read_indices(model_, prim.indices, positions.size(), file_, what);
  } else {
    for (std::uint32_t i = 0; i < positions.size(); ++i) indices.push_back(i);
  }
  if (prim.mode == TINYGLTF_MODE_TRIANGLES && indices.size() % 3 != 0) {
    fail(file_, what + " has " + std::to_string(indices.size()) +
                    " entries, not a multiple of 3 as triangles need: " + gltf::kReexport);
  }
  uint material = material_index(prim.material);
  // TEXCOORD_n where a texture (slots by kSlot*) reads it, COLOR_0 where the primitive has one.
  const MaterialTextures& mt = material_textures_[material];
  const uint slots[7] = {mt.base_color, mt.emissive, mt.metallic_roughness, mt.specular, mt.specular_color,
                         mt.normal, mt.transmission};
  bool reads_set[2] = {false, false};
  for (uint k = 0; k < 7; ++k) {
    if (slots[k] != kNoTexture) reads_set[(mt.tex_coord_sets >> k) & 1u] = true;
  }
  const bool textured = reads_set[0] || reads_set[1];
  const bool masked = mt.alpha_cutoff > 0.0f;
  std::vector<glm::vec2> uv[2];
  std::vector<glm::vec4> colors;
  for (int set = 0; set < 2; ++set) {
    if (!reads_set[set]) continue;
    const std::string name = "TEXCOORD_" + std::to_string(set);
    auto texcoord = prim.attributes.find(name);
    if (texcoord != prim.attributes.end()) {
      uv[set] = gltf::read_texcoords(model_, texcoord->second, positions.size(), file_,
                                     "accessors[" + std::to_string(texcoord->second) + "] (" + name + " of " + where + ")");
    } else {
      warn_once(file_ + ": " + where + " has a texture on " + name + " but no " + name +
                "; its textures there are read at uv (0, 0)");
    }
  }
  auto color = prim.attributes.find("COLOR_0");
  if (color != prim.attributes.end()) {
    colors = gltf::read_colors(model_, color->second, positions.size(), file_,
                               "accessors[" + std::to_string(color->second) + "] (COLOR_0 of " + where + ")");
  }
  // The attributes start with the first triangle that needs them (those before get the defaults).
  if ((textured || masked || !colors.empty()) && !attributes_on_) {
    attributes_.assign(scene_.triangles.size(), no_triangle_attributes());
    attributes_on_ = true;
  }
  // NORMAL and TANGENT, kept from the first primitive that has normals or a normal map.
  gltf::PrimitiveShading shading = gltf::read_shading(model_, prim, positions.size(), file_, where);
  if ((!shading.normals.empty() || mt.normal != kNoTexture) && !shading_on_) {
    for (const Triangle& t : scene_.triangles) shading_.push_back(flat_shading(t));
    shading_on_ = true;
  }
  indices = gltf::triangulate(prim.mode, indices);
  for (const glm::dmat4& world : worlds) {
    add_triangles(indices, positions, world, material, uv[0], uv[1], colors, shading);
  }
}

void SceneBuilder::add_triangles(const std::vector<std::uint32_t>& indices, const std::vector<glm::vec3>& positions,
                                 const glm::dmat4& world, uint material, const std::vector<glm::vec2>& uv,
                                 const std::vector<glm::vec2>& uv_set1, const std::vector<glm::vec4>& colors,
                                 const PrimitiveShading& shading) {
  for (std::size_t t = 0; t < indices.size(); t += 3) {
    glm::vec3 p[3];
    for (int k = 0; k < 3; ++k) p[k] = glm::vec3(world * glm::dvec4(positions[indices[t + k]], 1.0));
    // Skip what has no area once in 32-bit floats (or overflowed)
    glm::dvec3 n = glm::cross(glm::dvec3(p[1]) - glm::dvec3(p[0]), glm::dvec3(p[2]) - glm::dvec3(p[0]));
    if (!(glm::dot(n, n) > 0.0) || !std::isfinite(glm::dot(n, n))) {
      ++scene_.degenerate_triangles;
      continue;
    }
    scene_.add_triangle(p[0], p[1], p[2], material);
    if (shading_on_) {
      glm::vec2 corner_uv[3] = {glm::vec2(0.0f), glm::vec2(0.0f), glm::vec2(0.0f)};
      // Tangents from the set the normal map reads (TEXCOORD_0 or TEXCOORD_1).
      const std::vector<glm::vec2>& map_uv =
          (material_textures_[material].tex_coord_sets >> kSlotNormal & 1u) ? uv_set1 : uv;
      if (!map_uv.empty()) {
        corner_uv[0] = map_uv[indices[t]], corner_uv[1] = map_uv[indices[t + 1]], corner_uv[2] = map_uv[indices[t + 2]];
      }
      TriangleShading s;
      const bool mapped = material_textures_[material].normal != kNoTexture;
      if (gltf::shade_triangle(shading, &indices[t], p, corner_uv, world, mapped, s)) {
        scene_.triangles.back().flags |= kTriangleShadingNormals;
      }
      shading_.push_back(s);
    }
    if (!attributes_on_) continue;
    TriangleAttributes a = no_triangle_attributes();
    if (!uv.empty()) a.uv0 = uv[indices[t]], a.uv1 = uv[indices[t + 1]], a.uv2 = uv[indices[t + 2]];
    if (!uv_set1.empty()) {
      a.set1_uv0 = uv_set1[indices[t]], a.set1_uv1 = uv_set1[indices[t + 1]], a.set1_uv2 = uv_set1[indices[t + 2]];
    }
    if (!colors.empty()) {
      a.color0 = colors[indices[t]], a.color1 = colors[indices[t + 1]], a.color2 = colors[indices[t + 2]];
    }
    attributes_.push_back(a);
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
