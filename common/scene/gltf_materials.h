// glTF materials as the contract's (README.md, "Materials"), for the glTF loader
// (gltf_loader.cpp): metallic-roughness factors and the KHR_materials_emissive_strength,
// KHR_materials_transmission, KHR_materials_ior and KHR_materials_specular extensions, every
// number checked.
#pragma once

#include <string>

#include <tiny_gltf.h>

#include "common/kernel/scene_types.h"

namespace pt::gltf {

// model.materials[index] as a pt::Material; `file` names the scene in error messages.
Material convert_material(const tinygltf::Model& model, int index, const std::string& file);

// KHR_materials_specular's specularColorFactor of a material (`where` names it), or white:
// three numbers, each at least 0 (exit 3 otherwise).
glm::vec3 specular_color_factor(const tinygltf::ExtensionMap& extensions, const std::string& where,
                                const std::string& file);

}  // namespace pt::gltf
