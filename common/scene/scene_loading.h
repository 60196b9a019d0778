// Where scenes come from: a glTF 2.0 file read by the rules of the contract (README.md) ("Scenes"),
// or a built-in scene by name (builtin_scenes.cpp). Errors throw pt::Error with exit 3.
#pragma once

#include <string>
#include <vector>

#include "common/scene/scene.h"

namespace pt {

// "builtin:NAME" or a path to a .gltf / .glb file; gltf_scene: --gltf-scene's choice of the
// file's scenes ("" = its default; refused with exit 2 for a built-in scene).
Scene load_scene(const std::string& spec, const std::string& gltf_scene = "");

// A glTF 2.0 file (.gltf or .glb): every triangle primitive (lists, strips, fans) of the default
// scene, or of scene_choice (its index or name), with node transforms and EXT_mesh_gpu_instancing
// applied, materials, punctual lights and the cameras. Unsupported features are named once on
// stderr; malformed files and files with no triangle to draw throw pt::Error(kExitBadScene, ...),
// a scene_choice the file does not have pt::Error(kExitBadOption, ...).
Scene load_gltf(const std::string& path, const std::string& scene_choice = "");

struct BuiltinInfo {
  std::string name;         // used as builtin:NAME
  std::string description;  // one line, shown by --help
};
const std::vector<BuiltinInfo>& builtin_scenes();
Scene make_builtin_scene(const std::string& name);  // throws pt::Error(3) for unknown names

}  // namespace pt
