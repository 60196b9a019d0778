// Checks of a glTF 2.0 file that tinygltf leaves to its user, for the loader of
// the contract (README.md) "Scenes": after tinygltf has read it, the extensions used, every
// reference between arrays and the node tree; and the one-line failure every check ends in.
// The file before tinygltf: gltf_precheck.cpp; the accessors a triangle reads: gltf_accessors.cpp.
#include "common/scene/gltf_validate.h"

#include <cmath>
#include <cstdio>
#include <set>

#include "common/base/error.h"
#include "common/scene/gltf_validate_detail.h"

namespace pt::gltf {

using namespace detail;

namespace {

// extensionsRequired is checked before tinygltf runs (gltf_precheck.cpp): an extension
// such as Draco changes what the buffers hold. What remains is to name, once, the
// extensions a file uses that are not modelled.
void warn_unsupported_extensions(const tinygltf::Model& model, const std::string& file) {
  std::string ignored;
  for (const std::string& name : model.extensionsUsed) {
    if (!kSupportedExtensions.count(name)) ignored += (ignored.empty() ? "" : ", ") + name;
  }
  if (!ignored.empty()) warn_once(file + ": scene uses extensions " + ignored + "; they are not modelled");
}

// EXT_mesh_gpu_instancing: TRANSLATION, ROTATION and SCALE (each optional) name accessors of
// one count, the instances; their types are checked as they are read (read_instance_attribute).
void check_instancing(const tinygltf::Model& model, const tinygltf::Node& node, const std::string& where,
                      const std::string& file) {
  auto ext = node.extensions.find("EXT_mesh_gpu_instancing");
  if (ext == node.extensions.end() || !ext->second.Has("attributes")) return;
  const tinygltf::Value& attributes = ext->second.Get("attributes");
  const std::string w = where + ".extensions.EXT_mesh_gpu_instancing.attributes";
  if (!attributes.IsObject()) fail(file, w + " is not an object: " + std::string(kReexport));
  std::string first;
  std::size_t count = 0;
  for (const char* name : {"TRANSLATION", "ROTATION", "SCALE"}) {
    if (!attributes.Has(name)) continue;
    const tinygltf::Value& v = attributes.Get(name);
    if (!v.IsInt()) fail(file, w + "." + name + " is not an integer: " + std::string(kReexport));
    check_index(file, v.GetNumberAsInt(), model.accessors.size(), w + "." + name, "accessors");
    const std::size_t n = model.accessors[std::size_t(v.GetNumberAsInt())].count;
    if (!first.empty() && n != count) {
      fail(file, w + "." + name + " has " + str(n) + " instances, " + first + " has " + str(count) +
                     ": every instancing attribute has one per instance; " + kReexport);
    }
    if (first.empty()) first = name, count = n;
  }
}

void check_node(const tinygltf::Model& model, std::size_t i, const std::string& file) {
  const tinygltf::Node& node = model.nodes[i];
  std::string where = "nodes[" + str(i) + "]";
  if (node.mesh != -1) check_index(file, node.mesh, model.meshes.size(), where + ".mesh", "meshes");
  if (node.camera != -1) check_index(file, node.camera, model.cameras.size(), where + ".camera", "cameras");
  if (node.skin != -1) check_index(file, node.skin, model.skins.size(), where + ".skin", "skins");
  for (std::size_t k = 0; k < node.children.size(); ++k) {
    check_index(file, node.children[k], model.nodes.size(), where + ".children[" + str(k) + "]", "nodes");
  }
  auto light = node.extensions.find("KHR_lights_punctual");
  if (light != node.extensions.end()) {
    std::string w = where + ".extensions.KHR_lights_punctual.light";
    if (!light->second.Has("light") || !light->second.Get("light").IsInt()) {
      fail(file, w + " is missing or not an integer: " + std::string(kReexport));
    }
    check_index(file, light->second.Get("light").GetNumberAsInt(), model.lights.size(), w, "lights");
  }
  check_instancing(model, node, where, file);
  // Transforms: a full matrix, or translation / rotation / scale of the right lengths
  const std::pair<const std::vector<double>*, std::pair<const char*, std::size_t>> parts[] = {
      {&node.matrix, {"matrix", 16}},
      {&node.translation, {"translation", 3}},
      {&node.rotation, {"rotation", 4}},
      {&node.scale, {"scale", 3}}};
  for (const auto& [values, name_size] : parts) {
    std::string w = where + "." + name_size.first;
    if (!values->empty() && values->size() != name_size.second) {
      fail(file,
           w + " has " + str(values->size()) + " numbers, needs " + str(name_size.second) + ": " + kReexport);
    }
    for (std::size_t k = 0; k < values->size(); ++k)
      checked_float(file, (*values)[k], w + "[" + str(k) + "]");
  }
  double q2 = 0.0;
  for (double q : node.rotation) q2 += q * q;
  if (!node.rotation.empty() && !(q2 > 1e-12))
    fail(file, where + ".rotation is a zero quaternion: " + std::string(kReexport));
}

// One parent per node and no cycles; scenes list roots, each once.
std::vector<int> check_tree(const tinygltf::Model& model, const std::string& file) {
  std::size_t n = model.nodes.size();
  std::vector<int> parent(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    for (int c : model.nodes[i].children) {
      std::string child = "nodes[" + std::to_string(c) + "]", self = "nodes[" + str(i) + "]";
      if (std::size_t(c) == i)
        fail(file, self + " is its own child: the node tree has a cycle; " + kReexport);
      if (parent[c] == int(i)) fail(file, child + " is listed twice in " + self + ".children: " + kReexport);
      if (parent[c] != -1) {
        fail(file, child + " is a child of both nodes[" + std::to_string(parent[c]) + "] and " + self +
                       ": glTF nodes form trees; " + kReexport);
      }
      parent[c] = int(i);
    }
  }
  std::vector<char> state(n, 0);  // 0 unseen, 1 on the chain being followed, 2 known acyclic
  for (std::size_t i = 0; i < n; ++i) {
    int j = int(i);
    while (j != -1 && state[j] == 0) state[j] = 1, j = parent[j];
    if (j != -1 && state[j] == 1) {
      fail(file,
           "nodes[" + std::to_string(j) + "] is its own ancestor: the node tree has a cycle; " + kReexport);
    }
    for (j = int(i); j != -1 && state[j] == 1; j = parent[j]) state[j] = 2;
  }
  for (std::size_t s = 0; s < model.scenes.size(); ++s) {
    std::set<int> listed;
    for (std::size_t k = 0; k < model.scenes[s].nodes.size(); ++k) {
      int r = model.scenes[s].nodes[k];
      std::string where = "scenes[" + str(s) + "].nodes[" + str(k) + "]";
      check_index(file, r, n, where, "nodes");
      if (parent[r] != -1) {
        fail(file, where + " = " + std::to_string(r) + " is a child of nodes[" + std::to_string(parent[r]) +
                       "]; a scene lists root nodes only: " + kReexport);
      }
      if (!listed.insert(r).second)
        fail(file, where + " lists nodes[" + std::to_string(r) + "] twice: " + kReexport);
    }
  }
  return parent;
}

}  // namespace

void fail(const std::string& file, const std::string& message) {
  std::string line = file + ": " + message;
  for (char& c : line) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  throw Error(kExitBadScene, line);
}

float checked_float(const std::string& file, double value, const std::string& where, double lo, double hi) {
  float f = float(value);
  if (!std::isfinite(f)) fail(file, where + " is not a finite 32-bit float: " + std::string(kReexport));
  if (!(value >= lo && value <= hi)) {
    char range[64];
    std::snprintf(range, sizeof range, "[%g, %g]", lo, hi);
    fail(file, where + " = " + std::to_string(value) + " is outside " + range + ": " + kReexport);
  }
  return f;
}

std::vector<int> check_model(const tinygltf::Model& model, const std::string& file) {
  warn_unsupported_extensions(model, file);
  if (model.defaultScene != -1) check_index(file, model.defaultScene, model.scenes.size(), "scene", "scenes");
  for (std::size_t i = 0; i < model.nodes.size(); ++i) check_node(model, i, file);
  for (std::size_t m = 0; m < model.meshes.size(); ++m) {
    for (std::size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
      const tinygltf::Primitive& prim = model.meshes[m].primitives[p];
      std::string where = "meshes[" + str(m) + "].primitives[" + str(p) + "]";
      if (prim.mode < 0 || prim.mode > 6) {
        fail(file, where + ".mode is " + std::to_string(prim.mode) +
                       ", not one of glTF's modes 0-6 (points, lines, line loop, line strip, triangles, triangle "
                       "strip, triangle fan): " + kReexport);
      }
      if (prim.material != -1)
        check_index(file, prim.material, model.materials.size(), where + ".material", "materials");
      if (prim.indices != -1)
        check_index(file, prim.indices, model.accessors.size(), where + ".indices", "accessors");
      for (const auto& [name, accessor] : prim.attributes) {
        check_index(file, accessor, model.accessors.size(), where + ".attributes." + name, "accessors");
      }
    }
  }
  return check_tree(model, file);
}

}  // namespace pt::gltf
