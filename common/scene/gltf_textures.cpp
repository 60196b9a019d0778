// glTF textures (see gltf_textures.h): the texture slots of a material with their samplers
// and KHR_texture_transform, and the texture table: the images it uses (each once), their
// headers checked against kMaxTextureSize (gltf_images.cpp opens them) and all together
// against kMaxTexelBytes before any is decoded, then decoded into Scene::texels.
// Not part of the article: the contract's (README.md) "Materials" textures.
#include "common/scene/gltf_textures.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "common/base/error.h"
#include "common/scene/gltf_images.h"
#include "common/scene/gltf_materials.h"
#include "common/scene/gltf_validate.h"
#include "common/scene/gltf_validate_detail.h"

namespace pt::gltf {

using namespace detail;

namespace {

constexpr int kGlRepeat = 10497, kGlClampToEdge = 33071, kGlMirroredRepeat = 33648;
constexpr int kGlNearest = 9728, kGlLinear = 9729;

// The encoded bytes of model.images[index]: its bufferView's, or those keep_image_bytes kept.
std::span<const unsigned char> image_bytes(const tinygltf::Model& model, int index, const std::string& file,
                                           const std::string& what) {
  const tinygltf::Image& image = model.images[index];
  if (image.bufferView >= 0) {
    check_index(file, image.bufferView, model.bufferViews.size(), "images[" + str(index) + "].bufferView",
                "bufferViews");
    const tinygltf::BufferView& view = model.bufferViews[image.bufferView];
    check_index(file, view.buffer, model.buffers.size(), "bufferViews[" + str(image.bufferView) + "].buffer",
                "buffers");
    const std::vector<unsigned char>& data = model.buffers[view.buffer].data;
    std::uint64_t end = 0;
    if (__builtin_add_overflow(std::uint64_t(view.byteOffset), std::uint64_t(view.byteLength), &end) ||
        end > data.size()) {
      fail(file, what + ": bufferViews[" + str(image.bufferView) + "] runs past buffers[" + str(view.buffer) +
                     "] (" + need_text(false, end, data.size()) + "): " + kReexport);
    }
    return {data.data() + view.byteOffset, view.byteLength};
  }
  if (!image.image.empty()) return image.image;
  if (!image.uri.empty()) {
    fail(file, what + " was not found next to the scene: copy the file there (or embed it) and load again");
  }
  fail(file, what + " has no data (neither a bufferView nor a uri): " + std::string(kReexport));
}

// "images[2] 'wood.png' (base colour texture of materials[0])": the image as messages name it.
std::string image_name(const tinygltf::Model& model, int index, const std::string& use) {
  const tinygltf::Image& image = model.images[index];
  std::string name = "images[" + str(index) + "]";
  if (!image.uri.empty()) name += " '" + image.uri.substr(0, 80) + "'";
  else if (!image.name.empty()) name += " '" + image.name.substr(0, 80) + "'";
  return name + " (" + use + ")";
}

uint wrap_mode(int gl, const std::string& where, const std::string& file) {
  if (gl == kGlRepeat) return kWrapRepeat;
  if (gl == kGlClampToEdge) return kWrapClampToEdge;
  if (gl == kGlMirroredRepeat) return kWrapMirroredRepeat;
  fail(file, where + " = " + std::to_string(gl) +
                 " is not a glTF wrap mode (REPEAT 10497, CLAMP_TO_EDGE 33071, MIRRORED_REPEAT 33648): " +
                 kReexport);
}

// A number of KHR_texture_transform, or its default.
double transform_number(const tinygltf::Value& ext, const char* key, int element, double fallback,
                        const std::string& where, const std::string& file) {
  if (!ext.Has(key)) return fallback;
  const tinygltf::Value& v = ext.Get(key);
  std::string w = where + ".extensions.KHR_texture_transform." + key;
  if (element >= 0) {
    if (!v.IsArray() || v.ArrayLen() != 2) fail(file, w + " needs 2 numbers: " + std::string(kReexport));
    w += "[" + std::to_string(element) + "]";
    const tinygltf::Value& e = v.Get(element);
    if (!e.IsNumber()) fail(file, w + " is not a number: " + std::string(kReexport));
    return checked_float(file, e.GetNumberAsDouble(), w);
  }
  if (!v.IsNumber()) fail(file, w + " is not a number: " + std::string(kReexport));
  return checked_float(file, v.GetNumberAsDouble(), w);
}

// A texture of an extension (KHR_materials_specular's) as glTF's textureInfo: its index,
// texCoord and KHR_texture_transform; index -1 where the extension has no such texture.
tinygltf::TextureInfo extension_texture(const tinygltf::ExtensionMap& extensions, const char* extension,
                                        const char* key, const std::string& where, const std::string& file) {
  tinygltf::TextureInfo info;
  auto ext = extensions.find(extension);
  if (ext == extensions.end() || !ext->second.Has(key)) return info;
  const tinygltf::Value& v = ext->second.Get(key);
  if (!v.IsObject() || !v.Has("index") || !v.Get("index").IsInt())
    fail(file, where + " has no integer index: " + std::string(kReexport));
  info.index = v.Get("index").GetNumberAsInt();
  if (v.Has("texCoord")) {
    if (!v.Get("texCoord").IsInt()) fail(file, where + ".texCoord is not an integer: " + std::string(kReexport));
    info.texCoord = v.Get("texCoord").GetNumberAsInt();
  }
  if (v.Has("extensions") && v.Get("extensions").Has("KHR_texture_transform"))
    info.extensions["KHR_texture_transform"] = v.Get("extensions").Get("KHR_texture_transform");
  return info;
}

}  // namespace

uint TextureBuilder::texture_slot(const tinygltf::TextureInfo& info, const std::string& where, uint slot,
                                  MaterialTextures& mt, glm::vec3& row_s, glm::vec3& row_t) {
  if (info.index < 0) return kNoTexture;
  check_index(file_, info.index, model_.textures.size(), where + ".index", "textures");
  // KHR_texture_transform: (s, t) = T(offset) R(rotation) S(scale) (u, v, 1), with the
  // rotation's sign of the extension's example (a quarter turn of offset (0, 1), scale
  // 0.5 maps the unit square onto the image's lower-left quadrant).
  int tex_coord = info.texCoord;
  auto ext = info.extensions.find("KHR_texture_transform");
  double ox = 0.0, oy = 0.0, rotation = 0.0, sx = 1.0, sy = 1.0;
  if (ext != info.extensions.end()) {
    const tinygltf::Value& t = ext->second;
    ox = transform_number(t, "offset", 0, 0.0, where, file_), oy = transform_number(t, "offset", 1, 0.0, where, file_);
    sx = transform_number(t, "scale", 0, 1.0, where, file_), sy = transform_number(t, "scale", 1, 1.0, where, file_);
    rotation = transform_number(t, "rotation", -1, 0.0, where, file_);
    if (t.Has("texCoord") && t.Get("texCoord").IsInt()) tex_coord = t.Get("texCoord").GetNumberAsInt();
  }
  const double c = std::cos(rotation), s = std::sin(rotation);
  row_s = glm::vec3(float(c * sx), float(s * sy), float(ox));
  row_t = glm::vec3(float(-s * sx), float(c * sy), float(oy));
  // TEXCOORD_0 and TEXCOORD_1 are read (the slot's bit of tex_coord_sets: texture_lookup.glsl slot_uv).
  if (tex_coord == 1) {
    mt.tex_coord_sets |= 1u << slot;
  } else if (tex_coord != 0) {
    warn_once(file_ + ": scene has textures read through TEXCOORD_" + std::to_string(tex_coord) +
              "; only TEXCOORD_0 and TEXCOORD_1 are modelled, so they are read through TEXCOORD_0");
  }
  auto found = by_texture_.find(info.index);
  if (found != by_texture_.end()) return found->second;
  const tinygltf::Texture& texture = model_.textures[info.index];
  std::string tex_where = "textures[" + std::to_string(info.index) + "]";
  if (texture.source < 0) {
    warn_once(file_ + ": " + tex_where + " has no PNG or JPEG source (only an extension's image); the " +
              "materials using it are drawn with their factors");
    return by_texture_[info.index] = kNoTexture;
  }
  check_index(file_, texture.source, model_.images.size(), tex_where + ".source", "images");
  Texture entry{};
  entry.wrap_s = entry.wrap_t = kWrapRepeat;
  entry.mag_filter = kFilterLinear;
  if (texture.sampler >= 0) {
    check_index(file_, texture.sampler, model_.samplers.size(), tex_where + ".sampler", "samplers");
    const tinygltf::Sampler& sampler = model_.samplers[texture.sampler];
    std::string s_where = "samplers[" + std::to_string(texture.sampler) + "]";
    entry.wrap_s = wrap_mode(sampler.wrapS, s_where + ".wrapS", file_);
    entry.wrap_t = wrap_mode(sampler.wrapT, s_where + ".wrapT", file_);
    if (sampler.magFilter == kGlNearest) {
      entry.mag_filter = kFilterNearest;
    } else if (sampler.magFilter != -1 && sampler.magFilter != kGlLinear) {
      fail(file_, s_where + ".magFilter = " + std::to_string(sampler.magFilter) +
                      " is neither NEAREST (9728) nor LINEAR (9729): " + kReexport);
    }
  }
  table_.push_back(entry);
  table_image_.push_back(texture.source);
  table_use_.push_back(where);
  return by_texture_[info.index] = uint(table_.size() - 1);
}

MaterialTextures TextureBuilder::material_textures(int material, const Material& made) {
  const tinygltf::Material& m = model_.materials[material];
  const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
  std::string where = "materials[" + std::to_string(material) + "]";
  MaterialTextures t = no_material_textures();
  t.base_color = texture_slot(pbr.baseColorTexture, where + ".pbrMetallicRoughness.baseColorTexture",
                              kSlotBaseColor, t, t.base_color_s, t.base_color_t);
  t.emissive = texture_slot(m.emissiveTexture, where + ".emissiveTexture", kSlotEmissive, t, t.emissive_s,
                            t.emissive_t);
  t.metallic_roughness = texture_slot(pbr.metallicRoughnessTexture,
                                      where + ".pbrMetallicRoughness.metallicRoughnessTexture",
                                      kSlotMetallicRoughness, t, t.metallic_roughness_s, t.metallic_roughness_t);
  // The factors, checked by convert_material (gltf_materials.cpp) already.
  t.metallic_factor = float(pbr.metallicFactor);
  t.roughness_factor = float(pbr.roughnessFactor);
  if (m.alphaMode == "MASK") {  // alpha below the cutoff is a hole (intersect.glsl cut_out)
    t.alpha_cutoff = checked_float(file_, m.alphaCutoff, where + ".alphaCutoff", 0.0);
    t.base_alpha = pbr.baseColorFactor.size() == 4
                       ? checked_float(file_, pbr.baseColorFactor[3], where + ".pbrMetallicRoughness.baseColorFactor[3]", 0.0, 1.0)
                       : 1.0f;
  }
  if (m.normalTexture.index >= 0) {  // a tangent-space normal map (common/kernel/shading_normal.glsl)
    tinygltf::TextureInfo info;
    info.index = m.normalTexture.index, info.texCoord = m.normalTexture.texCoord;
    info.extensions = m.normalTexture.extensions;
    t.normal = texture_slot(info, where + ".normalTexture", kSlotNormal, t, t.normal_s, t.normal_t);
    t.normal_scale = checked_float(file_, m.normalTexture.scale, where + ".normalTexture.scale");
  }
  if (m.occlusionTexture.index >= 0) {
    warn_once(file_ + ": scene has occlusion textures; they are not used (the path tracer finds occlusion itself)");
  }
  // KHR_materials_transmission's and KHR_materials_specular's textures (the factors are the
  // material's: gltf_materials.cpp), where the material is a glTF dielectric for them to vary.
  if (made.kind != kMaterialDielectric) return t;
  if (made.transmission > 0.0f) {  // transmissionTexture's R (linear) scales transmissionFactor
    const std::string transmission = where + ".extensions.KHR_materials_transmission.transmissionTexture";
    t.transmission = texture_slot(extension_texture(m.extensions, "KHR_materials_transmission", "transmissionTexture",
                                                    transmission, file_),
                                  transmission, kSlotTransmission, t, t.transmission_s, t.transmission_t);
  }
  const std::string specular = where + ".extensions.KHR_materials_specular.";
  t.specular = texture_slot(
      extension_texture(m.extensions, "KHR_materials_specular", "specularTexture", specular + "specularTexture", file_),
      specular + "specularTexture", kSlotSpecular, t, t.specular_s, t.specular_t);
  t.specular_color = texture_slot(extension_texture(m.extensions, "KHR_materials_specular", "specularColorTexture",
                                                    specular + "specularColorTexture", file_),
                                  specular + "specularColorTexture", kSlotSpecularColor, t, t.specular_color_s,
                                  t.specular_color_t);
  t.specular_color_factor = specular_color_factor(m.extensions, where, file_);
  return t;
}

void TextureBuilder::decode_into(Scene& scene) const {
  // Every image once, in the order first used; its header first, so that the limits are
  // checked before any texel is decoded.
  std::vector<int> images;
  std::vector<std::size_t> image_of(table_.size());
  for (std::size_t i = 0; i < table_.size(); ++i) {
    auto at = std::find(images.begin(), images.end(), table_image_[i]);
    image_of[i] = std::size_t(at - images.begin());
    if (at == images.end()) images.push_back(table_image_[i]);
  }
  std::vector<std::unique_ptr<OpenedImage>> opened;
  std::uint64_t total = 0;
  std::size_t largest = 0;
  for (std::size_t k = 0; k < images.size(); ++k) {
    std::size_t first_use = std::size_t(std::find(image_of.begin(), image_of.end(), k) - image_of.begin());
    std::string what = image_name(model_, images[k], table_use_[first_use]);
    opened.push_back(std::make_unique<OpenedImage>(image_bytes(model_, images[k], file_, what), file_, what));
    total += opened.back()->texels() * 4u;
    if (opened.back()->texels() > opened[largest]->texels()) largest = k;
  }
  if (total > kMaxTexelBytes) {
    fail(file_, "the textures need " + str(total >> 20) + " MiB of texels, more than the " +
                    str(kMaxTexelBytes >> 20) + " MiB limit (the largest is images[" + str(images[largest]) + "], " +
                    str(opened[largest]->width()) + " x " + str(opened[largest]->height()) +
                    "): downscale the images and re-export");
  }
  std::vector<std::uint32_t> offsets(images.size()), widths(images.size()), heights(images.size());
  std::vector<std::uint32_t> lo(images.size(), 0xffffffffu), hi(images.size(), 0u);
  scene.texels.clear();
  scene.texels.reserve(std::size_t(total / 4u));
  for (std::size_t k = 0; k < images.size(); ++k) {
    offsets[k] = std::uint32_t(scene.texels.size());
    widths[k] = opened[k]->width(), heights[k] = opened[k]->height();
    scene.texels.resize(scene.texels.size() + std::size_t(opened[k]->texels()));
    opened[k]->decode(scene.texels.data() + offsets[k]);
    // Each channel's smallest and largest texel (scene_features.cpp's feature mask reads them).
    std::uint32_t l[4] = {255, 255, 255, 255}, h[4] = {0, 0, 0, 0};
    for (std::size_t i = offsets[k]; i < scene.texels.size(); ++i) {
      for (int c = 0; c < 4; ++c) {
        std::uint32_t v = scene.texels[i] >> (8 * c) & 255u;
        l[c] = std::min(l[c], v), h[c] = std::max(h[c], v);
      }
    }
    lo[k] = l[0] | l[1] << 8 | l[2] << 16 | l[3] << 24;
    hi[k] = h[0] | h[1] << 8 | h[2] << 16 | h[3] << 24;
    opened[k].reset();
  }
  scene.textures = table_;
  for (std::size_t i = 0; i < table_.size(); ++i) {
    Texture& t = scene.textures[i];
    std::size_t k = image_of[i];
    t.offset = offsets[k], t.width = widths[k], t.height = heights[k];
    t.texel_min = lo[k], t.texel_max = hi[k];
  }
}

}  // namespace pt::gltf
