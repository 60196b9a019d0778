// glTF textures (see gltf_textures.h): the texture slots of a material with their samplers
// and KHR_texture_transform, and the images they use decoded by OpenImageIO from memory
// (PNG or JPEG; never by tinygltf; OpenImageIO is loaded then, common/base/openimageio.h), each checked against kMaxTextureSize and all together
// against kMaxTexelBytes before any is decoded.
#include "common/scene/gltf_textures.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>

#include "common/base/error.h"
#include "common/base/openimageio.h"
#include "common/scene/gltf_validate.h"
#include "common/scene/gltf_validate_detail.h"

namespace pt::gltf {

using namespace detail;

namespace {

constexpr int kGlRepeat = 10497, kGlClampToEdge = 33071, kGlMirroredRepeat = 33648;
constexpr int kGlNearest = 9728, kGlLinear = 9729;

// OpenImageIO's error text made short enough for a one-line message.
std::string short_error(std::string why) {
  for (char& c : why) c = (c == '\n' || c == '\r') ? ' ' : c;
  while (!why.empty() && (why.back() == ' ' || why.back() == '.')) why.pop_back();
  if (why.size() > 160) why = why.substr(0, 160) + "...";
  return why.empty() ? "no reason given" : why;
}

bool starts_with(std::span<const unsigned char> bytes, const char* magic, std::size_t n) {
  return bytes.size() >= n && std::memcmp(bytes.data(), magic, n) == 0;
}

// CRC-32 of PNG chunks (ISO 3309, as zlib's crc32).
std::uint32_t crc32(const unsigned char* p, std::size_t n, std::uint32_t crc = 0xffffffffu) {
  for (std::size_t i = 0; i < n; ++i) {
    crc ^= p[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return crc;
}

// The chunks of a PNG, checked before libpng sees them: each within the data with its CRC
// right, IHDR first, IEND last. libpng prints its own line on stderr for a damaged chunk
// before OpenImageIO reports it; this check names the damage in the one line instead.
void check_png_chunks(std::span<const unsigned char> bytes, const std::string& file, const std::string& what) {
  std::size_t at = 8;
  bool first = true;
  while (true) {
    if (bytes.size() - at < 12) {
      fail(file, what + " is a truncated PNG (no IEND chunk at its end): re-export it");
    }
    const unsigned char* c = bytes.data() + at;
    const std::uint64_t length = std::uint64_t(c[0]) << 24 | std::uint64_t(c[1]) << 16 | std::uint64_t(c[2]) << 8 | c[3];
    const std::string type(reinterpret_cast<const char*>(c + 4), 4);
    if (length > bytes.size() - at - 12) {
      fail(file, what + " is a truncated PNG (its chunk at byte " + str(at) + " runs past the end): re-export it");
    }
    const unsigned char* crc = c + 8 + length;
    const std::uint32_t stored = std::uint32_t(crc[0]) << 24 | std::uint32_t(crc[1]) << 16 | std::uint32_t(crc[2]) << 8 | crc[3];
    if ((crc32(c + 4, std::size_t(length) + 4) ^ 0xffffffffu) != stored) {
      fail(file, what + " is a damaged PNG (the CRC of its chunk at byte " + str(at) + " is wrong): re-export it");
    }
    if (first && type != "IHDR") fail(file, what + " is a damaged PNG (it does not start with IHDR): re-export it");
    first = false;
    at += 12 + std::size_t(length);
    if (type == "IEND") return;
  }
}

// libpng writes its errors on stderr itself as well as handing them to OpenImageIO, which
// hands them to us: while OpenImageIO reads, file descriptor 2 goes to /dev/null, so that a
// damaged image gives only fail()'s one line. The scene loads before any render thread
// starts, so nothing else is writing then.
class QuietStderr {
 public:
  QuietStderr() {
    std::fflush(stderr);
    saved_ = ::dup(2);
    const int null = ::open("/dev/null", O_WRONLY);
    if (saved_ >= 0 && null >= 0) ::dup2(null, 2);
    if (null >= 0) ::close(null);
  }
  ~QuietStderr() {
    if (saved_ < 0) return;
    std::fflush(stderr);
    ::dup2(saved_, 2);
    ::close(saved_);
  }
  QuietStderr(const QuietStderr&) = delete;
  QuietStderr& operator=(const QuietStderr&) = delete;

 private:
  int saved_ = -1;
};

// An image opened by OpenImageIO from memory: its header read, its texels not yet.
class OpenedImage {
 public:
  OpenedImage(std::span<const unsigned char> bytes, const std::string& file, const std::string& what)
      : file_(file), what_(what) {
    const bool png = starts_with(bytes, "\x89PNG\r\n\x1a\n", 8), jpeg = starts_with(bytes, "\xff\xd8\xff", 3);
    if (detail::is_lfs_pointer(bytes.data(), bytes.size())) {
      fail(file, what + " is a Git LFS pointer, not the image itself: " + detail::kLfsAdvice);
    }
    if (!png && !jpeg) {
      fail(file, what + " is neither a PNG nor a JPEG image: glTF images are PNG or JPEG; convert it and re-export");
    }
    if (png) check_png_chunks(bytes, file, what);
    std::string why;
    const ImageCodec* codec = openimageio(why);
    if (!codec) fail(file, what + ": " + why);
    {
      QuietStderr quiet;
      input_ = codec->open_memory(bytes.data(), bytes.size(), png, why);
    }
    if (!input_) {
      fail(file, what + " cannot be decoded (" + short_error(why) + "): the image is damaged or truncated; re-export it");
    }
    width_ = input_->width(), height_ = input_->height(), channels_ = input_->channels();
    if (channels_ < 1 || channels_ > 4) {
      fail(file, what + " has " + std::to_string(channels_) +
                     " channels; glTF images have 1 to 4: convert it to RGB or RGBA and re-export");
    }
    if (width_ <= 0 || height_ <= 0 || input_->depth() != 1) {
      fail(file, what + " has no texels (" + std::to_string(width_) + " x " + std::to_string(height_) +
                     "): re-export it");
    }
    if (std::uint64_t(width_) > kMaxTextureSize || std::uint64_t(height_) > kMaxTextureSize) {
      fail(file, what + " is " + std::to_string(width_) + " x " + std::to_string(height_) +
                     " texels, more than the " + std::to_string(kMaxTextureSize) + " x " +
                     std::to_string(kMaxTextureSize) + " an image may have: downscale it and re-export");
    }
  }

  std::uint32_t width() const { return std::uint32_t(width_); }
  std::uint32_t height() const { return std::uint32_t(height_); }
  std::uint64_t texels() const { return std::uint64_t(width()) * height(); }

  // Reads the texels as 8-bit RGBA into out[0 .. width * height), a few rows at a time.
  void decode(std::uint32_t* out) {
    const int channels = channels_;
    const int rows_per_read = 64;
    std::vector<unsigned char> rows(std::size_t(width_) * channels * rows_per_read);
    for (int y0 = 0; y0 < height_; y0 += rows_per_read) {
      const int y1 = std::min(height_, y0 + rows_per_read);
      bool read;
      {
        QuietStderr quiet;
        read = input_->read_rows(y0, y1, rows.data());
      }
      if (!read) {
        fail(file_, what_ + " cannot be decoded (" + short_error(input_->error()) +
                        "): the image is damaged or truncated; re-export it");
      }
      const std::size_t n = std::size_t(y1 - y0) * std::size_t(width_);
      for (std::size_t i = 0; i < n; ++i) {
        const unsigned char* p = &rows[i * channels];
        std::uint32_t r = p[0], g = channels >= 3 ? p[1] : p[0], b = channels >= 3 ? p[2] : p[0];
        std::uint32_t a = channels == 2 ? p[1] : channels == 4 ? p[3] : 255u;
        out[std::size_t(y0) * std::size_t(width_) + i] = r | g << 8 | b << 16 | a << 24;
      }
    }
  }

 private:
  std::string file_, what_;
  std::unique_ptr<ImageReader> input_;
  int width_ = 0, height_ = 0, channels_ = 0;  // the header's, read once
};

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

}  // namespace

bool keep_image_bytes(tinygltf::Image* image, int, std::string*, std::string*, int, int, const unsigned char* bytes,
                      int size, void*) {
  if (image->bufferView == -1 && bytes && size > 0) image->image.assign(bytes, bytes + size);
  return true;
}

DecodedImage decode_image(std::span<const unsigned char> bytes, const std::string& file, const std::string& what) {
  OpenedImage opened(bytes, file, what);
  DecodedImage image{opened.width(), opened.height(), std::vector<std::uint32_t>(opened.texels())};
  opened.decode(image.texels.data());
  return image;
}

uint TextureBuilder::texture_slot(const tinygltf::TextureInfo& info, const std::string& where, glm::vec3& row_s,
                                  glm::vec3& row_t) {
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
  if (tex_coord != 0) {
    warn_once(file_ + ": scene has textures read through TEXCOORD_" + std::to_string(tex_coord) +
              "; only TEXCOORD_0 is modelled, so they are read through TEXCOORD_0");
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

MaterialTextures TextureBuilder::material_textures(int material) {
  const tinygltf::Material& m = model_.materials[material];
  const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
  std::string where = "materials[" + std::to_string(material) + "]";
  MaterialTextures t = no_material_textures();
  t.base_color = texture_slot(pbr.baseColorTexture, where + ".pbrMetallicRoughness.baseColorTexture", t.base_color_s,
                              t.base_color_t);
  t.emissive = texture_slot(m.emissiveTexture, where + ".emissiveTexture", t.emissive_s, t.emissive_t);
  t.metallic_roughness = texture_slot(pbr.metallicRoughnessTexture,
                                      where + ".pbrMetallicRoughness.metallicRoughnessTexture",
                                      t.metallic_roughness_s, t.metallic_roughness_t);
  // The factors, checked by convert_material (gltf_materials.cpp) already.
  t.metallic_factor = float(pbr.metallicFactor);
  t.roughness_factor = float(pbr.roughnessFactor);
  if (m.alphaMode == "MASK") {  // alpha below the cutoff is a hole (intersect.glsl cut_out)
    t.alpha_cutoff = checked_float(file_, m.alphaCutoff, where + ".alphaCutoff", 0.0);
    t.base_alpha = pbr.baseColorFactor.size() == 4
                       ? checked_float(file_, pbr.baseColorFactor[3], where + ".pbrMetallicRoughness.baseColorFactor[3]", 0.0, 1.0)
                       : 1.0f;
  }
  if (m.normalTexture.index >= 0) {
    warn_once(file_ + ": scene has normal textures; they are not modelled (the geometric normal is used)");
  }
  if (m.occlusionTexture.index >= 0) {
    warn_once(file_ + ": scene has occlusion textures; they are not used (the path tracer finds occlusion itself)");
  }
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
    // Each channel's smallest and largest texel (scene.cpp's feature mask reads them).
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
