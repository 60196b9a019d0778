// glTF files with textures and two texture coordinate sets, written by the tests themselves
// (tests/common/scene/test_gltf_texcoord.cpp, tests/stages/test_texcoord_images.cpp): an
// embedded PNG texture, a quad with TEXCOORD_0 and TEXCOORD_1 at its corners, an
// orthographic camera. Not part of the article: test machinery (issue #46, texCoord).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "tests/support/gltf_writer.h"
#include "tests/support/png_bytes.h"

namespace pt::test {

inline constexpr int kGlClamp = 33071, kGlRepeatWrap = 10497, kGlNearestFilter = 9728;

// A texture of a width x height PNG of `texels` (rgba() packed, rows from the top), embedded
// in a bufferView, sampled NEAREST with `wrap` both ways; its index in textures[].
inline int image_texture(GltfWriter& g, std::uint32_t width, std::uint32_t height,
                         const std::vector<std::uint32_t>& texels, int wrap = kGlClamp) {
  std::vector<unsigned char> png = png_rgba(width, height, texels);
  int view = g.view(png.data(), png.size());
  int image = g.item("images", {{"bufferView", view}, {"mimeType", "image/png"}});
  int sampler = g.item("samplers", {{"magFilter", kGlNearestFilter}, {"wrapS", wrap}, {"wrapT", wrap}});
  return g.item("textures", {{"source", image}, {"sampler", sampler}});
}

// A quad p[0] p[1] p[2] p[3] (counter-clockwise seen from its front; triangles 012 and 023,
// no indices) with TEXCOORD_0 uv0 and, when uv1 is not empty, TEXCOORD_1 uv1 at its corners;
// its index in meshes[].
inline int textured_quad(GltfWriter& g, const std::vector<glm::vec3>& p, const std::vector<glm::vec2>& uv0,
                         const std::vector<glm::vec2>& uv1, int material) {
  const int order[6] = {0, 1, 2, 0, 2, 3};
  auto accessor = [&](const auto& corners, const char* type, int components, bool bounds) {
    std::vector<float> data;
    for (int k : order) {
      for (int c = 0; c < components; c++) data.push_back(corners[std::size_t(k)][c]);
    }
    int view = g.view(data.data(), data.size() * sizeof(float));
    GltfWriter::Json a = {{"bufferView", view}, {"componentType", 5126}, {"count", 6}, {"type", type}};
    if (bounds) {
      glm::vec3 lo(1e30f), hi(-1e30f);
      for (const glm::vec3& q : p) lo = glm::min(lo, q), hi = glm::max(hi, q);
      a["min"] = {lo.x, lo.y, lo.z}, a["max"] = {hi.x, hi.y, hi.z};
    }
    return g.item("accessors", a);
  };
  GltfWriter::Json attributes = {{"POSITION", accessor(p, "VEC3", 3, true)},
                                 {"TEXCOORD_0", accessor(uv0, "VEC2", 2, false)}};
  if (!uv1.empty()) attributes["TEXCOORD_1"] = accessor(uv1, "VEC2", 2, false);
  return g.item("meshes", {{"primitives", GltfWriter::Json::array({{{"attributes", attributes}, {"material", material}}})}});
}

// An orthographic camera of half-extents 1 x 1 on a node at `translation`, turned by the
// quaternion `rotation` (x, y, z, w).
inline void orthographic_camera(GltfWriter& g, glm::dvec3 translation, glm::dvec4 rotation = {0, 0, 0, 1}) {
  int camera = g.item("cameras", {{"type", "orthographic"},
                                  {"orthographic", {{"xmag", 1.0}, {"ymag", 1.0}, {"znear", 0.01}, {"zfar", 100.0}}}});
  g.node({{"camera", camera},
          {"translation", {translation.x, translation.y, translation.z}},
          {"rotation", {rotation.x, rotation.y, rotation.z, rotation.w}}});
}

}  // namespace pt::test
