// Where scenes come from: a glTF 2.0 file read by the rules of the contract (README.md) ("Scenes"),
// or a built-in scene by name (builtin_scenes.cpp). Errors throw pt::Error with exit 3.
#pragma once

#include <string>
#include <vector>

#include "common/scene/scene.h"

namespace pt {

// "builtin:NAME" or a path to a .gltf / .glb file.
Scene load_scene(const std::string& spec);

// A glTF 2.0 file (.gltf or .glb): every triangle primitive of the default scene with node
// transforms applied, materials, point lights and the first camera. Unsupported features
// are named once on stderr; malformed files throw pt::Error(kExitBadScene, ...).
Scene load_gltf(const std::string& path);

struct BuiltinInfo {
  std::string name;         // used as builtin:NAME
  std::string description;  // one line, shown by --help
};
const std::vector<BuiltinInfo>& builtin_scenes();
Scene make_builtin_scene(const std::string& name);  // throws pt::Error(3) for unknown names

}  // namespace pt
