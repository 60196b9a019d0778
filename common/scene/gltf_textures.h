// glTF textures for the loader (gltf_loader.cpp; issue #19, the contract (README.md)
// "Materials"): the base colour, emissive, metallic-roughness, KHR_materials_specular and
// KHR_materials_transmission textures of the materials a scene uses, with their samplers and KHR_texture_transform, and their images decoded by
// OpenImageIO (PNG or JPEG, from a bufferView, a data: URI or a file in the scene's
// folder) into the 8-bit RGBA texels of Scene::texels. tinygltf decodes nothing: its image
// loader only keeps the bytes (keep_image_bytes).
#pragma once

#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "common/scene/scene.h"

namespace pt::gltf {

// The largest image: texels along either side (what GPUs take as one 2-D texture).
inline constexpr std::uint32_t kMaxTextureSize = 16384;
// All the decoded texels of a scene together (4 bytes each): 1 GiB.
#ifndef FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION
inline constexpr std::uint64_t kMaxTexelBytes = std::uint64_t(1) << 30;
#else
// Under the fuzzer (tests/fuzz/, PT_FUZZ): 16 MiB. A 1-bit PNG of 33 KB is a legal
// 16384 x 16384 image that takes 9 s to decode (75 s with the sanitizers), which the
// fuzzer reports as a hang; with this budget each input stays fast and the same checks run.
inline constexpr std::uint64_t kMaxTexelBytes = std::uint64_t(1) << 24;
#endif

// tinygltf's image loader: decodes nothing, and keeps the encoded bytes of an image from a
// data: URI or an external file in image->image (an image in a bufferView is read from
// its buffer when it is decoded).
bool keep_image_bytes(tinygltf::Image* image, int index, std::string* err, std::string* warn, int width,
                      int height, const unsigned char* bytes, int size, void* user_data);

// An image decoded to 8-bit RGBA texels, packed R | G << 8 | B << 16 | A << 24, rows from
// the top. Grey images give R = G = B; images without alpha get A = 255; 16-bit images are
// rounded to 8 bits.
struct DecodedImage {
  std::uint32_t width = 0, height = 0;
  std::vector<std::uint32_t> texels;
};

// Decodes a PNG or JPEG image; `what` names it in the message of the pt::Error (exit 3)
// that a malformed, unsupported or oversized image (kMaxTextureSize) ends in.
DecodedImage decode_image(std::span<const unsigned char> bytes, const std::string& file, const std::string& what);

// The textures of the materials a scene uses: material_textures() notes which textures a
// material reads, decode_into() decodes the images they use (each once) when the scene is
// complete, so that images no drawn material references are never decoded.
class TextureBuilder {
 public:
  TextureBuilder(const tinygltf::Model& model, const std::string& file) : model_(model), file_(file) {}

  // The texture slots of model.materials[material] (texture table indices as they will be
  // once decode_into() has run), its factors, uv transforms and texture coordinate sets
  // (TEXCOORD_0 or TEXCOORD_1); names once what stays unmodelled (normal and occlusion
  // textures, texCoord 2 and above, which are read through TEXCOORD_0).
  // `made`: the material as convert_material made it. A glTF dielectric (kMaterialDielectric)
  // has the layer that KHR_materials_specular's textures vary, and where its transmission is
  // above 0 KHR_materials_transmission's transmissionTexture scales it; other materials
  // leave them unread.
  MaterialTextures material_textures(int material, const Material& made);

  // Whether some material noted a texture.
  bool empty() const { return table_.empty(); }

  // Decodes the images of every noted texture into scene.texels and fills scene.textures,
  // after checking every image's size and their total (kMaxTexelBytes): exit 3 otherwise.
  void decode_into(Scene& scene) const;

 private:
  // The table index of a texture slot (kSlot*) and its uv transform's rows; TEXCOORD_1
  // sets the slot's bit of mt.tex_coord_sets.
  uint texture_slot(const tinygltf::TextureInfo& info, const std::string& where, uint slot, MaterialTextures& mt,
                    glm::vec3& row_s, glm::vec3& row_t);

  const tinygltf::Model& model_;
  std::string file_;
  std::vector<Texture> table_;          // samplers set; offset, width, height by decode_into
  std::vector<int> table_image_;        // the glTF image of each entry
  std::vector<std::string> table_use_;  // what first used each entry, for messages
  std::map<int, uint> by_texture_;      // glTF texture index -> table index
};

}  // namespace pt::gltf
