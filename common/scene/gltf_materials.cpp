// glTF materials as the contract's (see gltf_materials.h): the factors and the extension
// numbers read, checked against their glTF ranges (and emission against kMaxEmission), and
// made a pt::Material by make_gltf_pbr_material (scene.cpp).
#include "common/scene/gltf_materials.h"

#include <cstdio>

#include "common/base/error.h"
#include "common/scene/gltf_validate.h"
#include "common/scene/scene.h"
#include "common/scene/scene_sanity.h"

namespace pt::gltf {

namespace {

// A number from a material extension, e.g. KHR_materials_ior.ior, or its default.
double extension_number(const tinygltf::ExtensionMap& extensions, const std::string& name,
                        const std::string& key, double fallback, const std::string& where,
                        const std::string& file) {
  auto it = extensions.find(name);
  if (it == extensions.end() || !it->second.Has(key)) return fallback;
  const tinygltf::Value& value = it->second.Get(key);
  if (!value.IsNumber())
    fail(file, where + ".extensions." + name + "." + key + " is not a number: " + gltf::kReexport);
  return value.GetNumberAsDouble();
}

// Emission that float sums could overflow (kMaxEmission, scene_sanity.h, says why) is
// refused: an image of +Inf pixels helps no one.
void check_emission(double radiance, const std::string& where, const std::string& file) {
  if (radiance <= kMaxEmission) return;
  char line[160];
  std::snprintf(line, sizeof line, " x emissiveStrength = %.3g is above %.0e, the largest emitted radiance ", radiance,
                kMaxEmission);
  fail(file, where + line +
                 "the renderer sums without overflowing 32-bit floats: lower KHR_materials_emissive_strength "
                 "(radiance is in the scene's own units; scale every light down together to keep the image's look)");
}

// A string from the file in a message: printable ASCII, at most 40 characters.
std::string printable(const std::string& text) {
  std::string out = text.substr(0, 40);
  for (char& c : out) c = (c >= ' ' && c <= '~') ? c : '?';
  return out + (text.size() > 40 ? "..." : "");
}

}  // namespace

glm::vec3 specular_color_factor(const tinygltf::ExtensionMap& extensions, const std::string& where,
                                const std::string& file) {
  auto it = extensions.find("KHR_materials_specular");
  if (it == extensions.end() || !it->second.Has("specularColorFactor")) return glm::vec3(1.0f);
  const tinygltf::Value& value = it->second.Get("specularColorFactor");
  std::string name = where + ".extensions.KHR_materials_specular.specularColorFactor";
  if (!value.IsArray() || value.ArrayLen() != 3) fail(file, name + " needs 3 numbers: " + gltf::kReexport);
  glm::vec3 color;
  for (int k = 0; k < 3; ++k) {
    const tinygltf::Value& c = value.Get(k);
    if (!c.IsNumber()) fail(file, name + "[" + std::to_string(k) + "] is not a number: " + gltf::kReexport);
    color[k] = checked_float(file, c.GetNumberAsDouble(), name + "[" + std::to_string(k) + "]", 0.0);
  }
  return color;
}

Material convert_material(const tinygltf::Model& model, int index, const std::string& file) {
  const tinygltf::Material& m = model.materials[index];
  const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
  std::string where = "materials[" + std::to_string(index) + "]";
  std::string factors = where + ".pbrMetallicRoughness.";
  if (pbr.baseColorFactor.size() != 4)
    fail(file, factors + "baseColorFactor needs 4 numbers: " + gltf::kReexport);
  glm::vec3 base, emission;
  double strength = extension_number(m.extensions, "KHR_materials_emissive_strength", "emissiveStrength",
                                     1.0, where, file);
  checked_float(file, strength, where + ".extensions.KHR_materials_emissive_strength.emissiveStrength",
                0.0);
  for (int k = 0; k < 3; ++k) {
    std::string i = "[" + std::to_string(k) + "]";
    base[k] = checked_float(file, pbr.baseColorFactor[k], factors + "baseColorFactor" + i, 0.0, 1.0);
    checked_float(file, m.emissiveFactor[k], where + ".emissiveFactor" + i, 0.0, 1.0);
    check_emission(m.emissiveFactor[k] * strength, where + ".emissiveFactor" + i, file);
    emission[k] = float(m.emissiveFactor[k] * strength);
  }
  float metallic = checked_float(file, pbr.metallicFactor, factors + "metallicFactor", 0.0, 1.0);
  float roughness = checked_float(file, pbr.roughnessFactor, factors + "roughnessFactor", 0.0, 1.0);
  double transmission =
      extension_number(m.extensions, "KHR_materials_transmission", "transmissionFactor", 0.0, where, file);
  double ior = extension_number(m.extensions, "KHR_materials_ior", "ior", 1.5, where, file);
  if (ior == 0.0) {
    warn_once(file + ": " + where + " has KHR_materials_ior ior 0, which is not modelled; using 1.5");
    ior = 1.5;
  }
  float t = checked_float(file, transmission,
                          where + ".extensions.KHR_materials_transmission.transmissionFactor", 0.0, 1.0);
  float eta = checked_float(file, ior, where + ".extensions.KHR_materials_ior.ior", 1.0);
  // MASK cuts holes (gltf_textures.cpp reads its cutoff; intersect.glsl cut_out).
  if (m.alphaMode != "OPAQUE" && m.alphaMode != "MASK")
    warn_once(file + ": scene uses alphaMode " + printable(m.alphaMode) + "; surfaces are drawn opaque");
  // KHR_materials_specular: the dielectric layer's weight and F0 colour (Appendix B's
  // fresnel_mix as the extension extends it; make_gltf_pbr_material, scene.cpp).
  double specular = extension_number(m.extensions, "KHR_materials_specular", "specularFactor", 1.0, where, file);
  GltfPbr pbr_material;
  pbr_material.base = base, pbr_material.metallic = metallic, pbr_material.roughness = roughness;
  pbr_material.transmission = t, pbr_material.ior = eta;
  pbr_material.specular =
      checked_float(file, specular, where + ".extensions.KHR_materials_specular.specularFactor", 0.0, 1.0);
  pbr_material.specular_color = specular_color_factor(m.extensions, where, file);
  pbr_material.emission = emission, pbr_material.double_sided = m.doubleSided;
  pbr_material.textured_metallic_roughness = pbr.metallicRoughnessTexture.index >= 0;
  // transmissionTexture's R scales the factor (gltf_textures.cpp reads it, texture.glsl applies it).
  auto tx = m.extensions.find("KHR_materials_transmission");
  pbr_material.textured_transmission = tx != m.extensions.end() && tx->second.Has("transmissionTexture");
  return make_gltf_pbr_material(pbr_material);
}

}  // namespace pt::gltf
