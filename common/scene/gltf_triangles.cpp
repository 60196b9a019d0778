// A glTF primitive as the scene's triangles (gltf_scene_builder.h, SceneBuilder::add_primitive),
// for the loader of the contract (README.md) "Scenes": its positions and indices read,
// strips and fans made triangles, each instance's transform applied, degenerate triangles
// skipped, and the texture coordinates, colours and shading frames its material needs.
// Not part of the article: how a file becomes the arrays the kernel searches.
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "common/base/error.h"
#include "common/scene/gltf_scene_builder.h"
#include "common/scene/gltf_validate.h"
#include "common/scene/scene.h"

namespace pt::gltf {

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
  // TEXCOORD_0 and TEXCOORD_1 where a texture of the material reads them, COLOR_0 where the
  // primitive has one; the attributes too where the material has an alpha mask.
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
  // A normal map without the file's TANGENT: per-vertex tangents from the set the map reads.
  const std::vector<glm::vec2>& map_uv = uv[(mt.tex_coord_sets >> kSlotNormal) & 1u];
  if (mt.normal != kNoTexture && shading.tangents.empty() && !shading.normals.empty() && !map_uv.empty()) {
    shading.tangents = gltf::vertex_tangents(positions, shading.normals, map_uv, indices);
  }
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

}  // namespace pt::gltf
