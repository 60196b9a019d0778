// What a glTF 2.0 file draws, for the loader of the contract (README.md) "Scenes" (gltf_loader.cpp):
// the scene chosen (the file's default `scene`, or --gltf-scene), triangle lists, strips and fans
// made triangles, points and lines counted and skipped, EXT_mesh_gpu_instancing's instances, and
// the triangles all of it will make, counted before any is made. Not part of the article.
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "common/base/error.h"
#include "common/scene/gltf_scene_builder.h"
#include "common/scene/gltf_validate.h"

namespace pt::gltf {

namespace {

bool material_needs_attributes(const tinygltf::Model& model, int index) {
  if (index < 0) return false;
  const tinygltf::Material& m = model.materials[std::size_t(index)];
  auto specular = m.extensions.find("KHR_materials_specular");
  bool specular_textures = specular != m.extensions.end() && (specular->second.Has("specularTexture") ||
                                                              specular->second.Has("specularColorTexture"));
  return m.pbrMetallicRoughness.baseColorTexture.index >= 0 || m.emissiveTexture.index >= 0 ||
         m.pbrMetallicRoughness.metallicRoughnessTexture.index >= 0 || m.normalTexture.index >= 0 ||
         m.alphaMode == "MASK" || specular_textures;
}

std::string scene_label(const tinygltf::Model& model, std::size_t s) {
  const std::string& name = model.scenes[s].name;
  return std::to_string(s) + (name.empty() ? "" : " '" + name + "'");
}

}  // namespace

const char* mode_name(int mode) {
  static const char* const kNames[] = {"POINTS",    "LINES",          "LINE_LOOP",     "LINE_STRIP",
                                       "TRIANGLES", "TRIANGLE_STRIP", "TRIANGLE_FAN"};
  return mode >= 0 && mode <= 6 ? kNames[mode] : "unknown";
}

std::uint64_t mode_triangles(int mode, std::uint64_t entries) {
  if (mode == TINYGLTF_MODE_TRIANGLES) return entries / 3;
  if (mode == TINYGLTF_MODE_TRIANGLE_STRIP || mode == TINYGLTF_MODE_TRIANGLE_FAN) return entries >= 3 ? entries - 2 : 0;
  return 0;
}

std::vector<std::uint32_t> triangulate(int mode, const std::vector<std::uint32_t>& v) {
  if (mode == TINYGLTF_MODE_TRIANGLES) return v;
  std::vector<std::uint32_t> out;
  if (v.size() < 3) return out;
  out.reserve(3 * (v.size() - 2));
  for (std::size_t i = 0; i + 2 < v.size(); ++i) {
    // The specification's orders: a strip's triangle i is (v[i], v[i+1], v[i+2]) for even i and
    // (v[i], v[i+2], v[i+1]) for odd i, so that all keep the first's winding; a fan's is
    // (v[i+1], v[i+2], v[0]), which winds as (v[0], v[i+1], v[i+2]).
    std::uint32_t a, b, c;
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      a = v[i], b = v[i + 1 + i % 2], c = v[i + 2 - i % 2];
    } else {
      a = v[0], b = v[i + 1], c = v[i + 2];
    }
    // A triangle naming a vertex twice is how strips join (and restart); it has no area.
    if (a == b || b == c || a == c) continue;
    out.insert(out.end(), {a, b, c});
  }
  return out;
}

std::uint64_t instance_count(const tinygltf::Model& model, const tinygltf::Node& node) {
  auto ext = node.extensions.find("EXT_mesh_gpu_instancing");
  if (ext == node.extensions.end() || !ext->second.Has("attributes")) return 1;
  const tinygltf::Value& attributes = ext->second.Get("attributes");
  for (const char* name : {"TRANSLATION", "ROTATION", "SCALE"}) {
    if (attributes.Has(name)) return model.accessors[std::size_t(attributes.Get(name).GetNumberAsInt())].count;
  }
  return 1;  // no attribute: the mesh once, where the node puts it
}

std::vector<glm::dmat4> instance_transforms(const tinygltf::Model& model, int node_index, const std::string& file) {
  const tinygltf::Node& node = model.nodes[std::size_t(node_index)];
  const std::size_t n = instance_count(model, node);
  std::vector<glm::dvec3> t(n, glm::dvec3(0.0)), s(n, glm::dvec3(1.0));
  std::vector<glm::dquat> r(n, glm::dquat(1.0, 0.0, 0.0, 0.0));
  auto ext = node.extensions.find("EXT_mesh_gpu_instancing");
  if (ext != node.extensions.end() && ext->second.Has("attributes")) {
    const tinygltf::Value& attributes = ext->second.Get("attributes");
    const std::string where = "nodes[" + std::to_string(node_index) + "].extensions.EXT_mesh_gpu_instancing.attributes.";
    for (const char* name : {"TRANSLATION", "ROTATION", "SCALE"}) {
      if (!attributes.Has(name)) continue;
      const int accessor = attributes.Get(name).GetNumberAsInt();
      const std::string what = "accessors[" + std::to_string(accessor) + "] (" + where + name + ")";
      const bool rotation = std::string(name) == "ROTATION";
      std::vector<float> f = read_instance_attribute(model, accessor, rotation ? 4 : 3, n, file, what);
      for (std::size_t i = 0; i < n; ++i) {
        const float* e = &f[i * (rotation ? 4 : 3)];
        if (rotation) {
          glm::dquat q(e[3], e[0], e[1], e[2]);  // glTF order: x, y, z, w
          if (!(glm::dot(q, q) > 1e-12)) fail(file, what + " entry " + std::to_string(i) + " is a zero quaternion: " + kReexport);
          r[i] = glm::normalize(q);
        } else {
          (std::string(name) == "SCALE" ? s : t)[i] = glm::dvec3(e[0], e[1], e[2]);
        }
      }
    }
  }
  // Each instance's TRS is in the node's space: world = node_world * T * R * S.
  std::vector<glm::dmat4> transforms(n);
  for (std::size_t i = 0; i < n; ++i) {
    transforms[i] = glm::scale(glm::translate(glm::dmat4(1.0), t[i]) * glm::mat4_cast(r[i]), s[i]);
  }
  return transforms;
}

DrawCount count_draws(const tinygltf::Model& model, const std::vector<int>& roots) {
  DrawCount count;
  std::vector<std::uint64_t> per_mesh(model.meshes.size(), 0);
  std::vector<bool> counted(model.meshes.size(), false);
  std::vector<int> stack(roots.rbegin(), roots.rend());
  while (!stack.empty()) {
    const tinygltf::Node& node = model.nodes[std::size_t(stack.back())];
    stack.pop_back();
    stack.insert(stack.end(), node.children.begin(), node.children.end());
    if (node.mesh < 0) continue;
    const std::size_t m = std::size_t(node.mesh);
    if (!counted[m]) {
      counted[m] = true;
      for (const tinygltf::Primitive& prim : model.meshes[m].primitives) {
        auto position = prim.attributes.find("POSITION");
        if (prim.mode >= 0 && prim.mode < 4) ++count.skipped[prim.mode];
        if (prim.mode < 4 || position == prim.attributes.end()) continue;
        const int accessor = prim.indices != -1 ? prim.indices : position->second;
        per_mesh[m] += mode_triangles(prim.mode, model.accessors[std::size_t(accessor)].count);  // < 2^31 each
        if (material_needs_attributes(model, prim.material) || prim.attributes.count("COLOR_0"))
          count.attributes = true;
        if (prim.attributes.count("NORMAL") ||
            (prim.material >= 0 && model.materials[std::size_t(prim.material)].normalTexture.index >= 0))
          count.shading = true;
      }
    }
    std::uint64_t placed = 0;  // the mesh's triangles once for every instance
    count.overflowed = count.overflowed || __builtin_mul_overflow(per_mesh[m], instance_count(model, node), &placed) ||
                       __builtin_add_overflow(count.triangles, placed, &count.triangles);
  }
  return count;
}

std::string skipped_text(const DrawCount& count) {
  std::string text;
  for (int mode = 0; mode < 4; ++mode) {
    if (count.skipped[mode] == 0) continue;
    text += (text.empty() ? "" : ", ") + std::to_string(count.skipped[mode]) + " primitive" +
            (count.skipped[mode] == 1 ? "" : "s") + " of mode " + mode_name(mode);
  }
  return text.empty() ? text : text + " skipped (points and lines are not drawn)";
}

std::vector<int> choose_scene(const tinygltf::Model& model, const std::vector<int>& parents, const std::string& request,
                              const std::string& file) {
  if (model.scenes.empty()) {
    if (!request.empty()) {
      throw Error(kExitBadOption, "--gltf-scene " + request + ": " + file +
                                      " has no scenes to choose from (it draws every root node); leave --gltf-scene out");
    }
    std::vector<int> roots;
    for (std::size_t i = 0; i < parents.size(); ++i) {
      if (parents[i] == -1) roots.push_back(int(i));
    }
    return roots;
  }
  std::size_t chosen = model.defaultScene == -1 ? 0 : std::size_t(model.defaultScene);
  if (!request.empty()) {
    std::string there;  // the scenes there are, for the message
    chosen = model.scenes.size();
    for (std::size_t s = 0; s < model.scenes.size() && chosen == model.scenes.size(); ++s) {
      bool by_index = request.find_first_not_of("0123456789") == std::string::npos && request.size() < 10 &&
                      std::stoul(request) == s;
      if (by_index || (!model.scenes[s].name.empty() && model.scenes[s].name == request)) chosen = s;
      there += (there.empty() ? "" : ", ") + scene_label(model, s);
    }
    if (chosen == model.scenes.size()) {
      throw Error(kExitBadOption, "--gltf-scene " + request + ": " + file + " has no such scene; its scenes: " + there +
                                      " (give the index or a name)");
    }
  } else if (model.scenes.size() > 1) {
    std::fprintf(stderr, "%s: the file has %zu scenes; drawing scene %s (--gltf-scene N|NAME picks another)\n",
                 file.c_str(), model.scenes.size(), scene_label(model, chosen).c_str());
  }
  return model.scenes[chosen].nodes;
}

}  // namespace pt::gltf
