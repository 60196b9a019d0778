// Tests of the glTF loader's accessor reading (common/scene/gltf_accessors.cpp) and of the
// checks before tinygltf runs (gltf_precheck.cpp): sparse accessors give the same mesh as
// dense ones and their faults one line each; texture coordinates and colours of every
// allowed component type read to known values; required extensions the renderer does not
// read and Git LFS pointers are named before any buffer is read. Fixtures: tests/data/gltf.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>

#include "common/scene/gltf_validate.h"
#include "tests/support/gltf_checks.h"

using namespace pt::test;

namespace {

// A fixture as tinygltf reads it, for calling the readers directly.
tinygltf::Model parse(const std::string& name) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  bool ok = loader.LoadASCIIFromFile(&model, &err, &warn, fixture(name));
  INFO(err);
  REQUIRE(ok);
  return model;
}

int attribute(const tinygltf::Model& model, int primitive, const char* name) {
  return model.meshes.at(0).primitives.at(primitive).attributes.at(name);
}

void check_uv(glm::vec2 got, glm::vec2 want) {
  INFO("got (" << got.x << ", " << got.y << "), want (" << want.x << ", " << want.y << ")");
  CHECK(got.x == Approx(want.x).margin(1e-6));
  CHECK(got.y == Approx(want.y).margin(1e-6));
}

void check_color(glm::vec4 got, glm::vec4 want) {
  INFO("got (" << got.r << ", " << got.g << ", " << got.b << ", " << got.a << ")");
  for (int c = 0; c < 4; ++c) CHECK(got[c] == Approx(want[c]).margin(1e-6));
}

}  // namespace

// --- Sparse accessors -----------------------------------------------------------------------

TEST_CASE("a sparse copy of a mesh loads to exactly the dense mesh's triangles", "[gltf][loader]") {
  pt::Scene dense = load("sparse_dense.gltf"), sparse = load("sparse.gltf");
  REQUIRE(dense.triangles.size() == 4);
  REQUIRE(sparse.triangles.size() == dense.triangles.size());
  for (std::size_t i = 0; i < dense.triangles.size(); ++i) {
    INFO("triangle " << i);
    CHECK(sparse.triangles[i].p0 == dense.triangles[i].p0);
    CHECK(sparse.triangles[i].p1 == dense.triangles[i].p1);
    CHECK(sparse.triangles[i].p2 == dense.triangles[i].p2);
  }
}

TEST_CASE("a sparse accessor without a bufferView is zeros with the substitutions", "[gltf][loader]") {
  pt::Scene scene = load("sparse_no_view.gltf");
  REQUIRE(scene.triangles.size() == 1);
  check_triangle(scene.triangles[0], {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
}

TEST_CASE("a sparse index past the accessor's count is an error", "[gltf][loader]") {
  require_bad_scene(
      fixture("sparse_index_past_count.gltf"),
      {"accessors[0] (POSITION of meshes[0].primitives[0])", "sparse index 1 is 5", "past its count (3)"});
}

TEST_CASE("sparse indices that do not strictly increase are an error", "[gltf][loader]") {
  require_bad_scene(fixture("sparse_not_increasing.gltf"),
                    {"accessors[0]", "sparse index 1 is 1", "(2)", "strictly increase"});
}

TEST_CASE("sparse indices running past their bufferView are an error", "[gltf][loader]") {
  require_bad_scene(fixture("sparse_indices_past_view.gltf"),
                    {"accessors[0]", "sparse.indices runs past bufferViews[0]", "needs 12 bytes, has 8"});
}

TEST_CASE("a sparse count too large for tinygltf's int is an error, not truncated", "[gltf][loader]") {
  require_bad_scene(fixture("sparse_count_too_large.gltf"),
                    {"accessors[0].sparse.count = 4294967298", "out of range"});
}

TEST_CASE("a sparse accessor cannot ask for gigabytes of zeros", "[gltf][loader]") {
  require_bad_scene(fixture("sparse_zeros_too_large.gltf"),
                    {"accessors[0]", "sparse without a bufferView", "count 33554432"});
}

// --- Texture coordinates and colours --------------------------------------------------------

TEST_CASE("texture coordinates of FLOAT and normalized u8 and u16 read to known values", "[gltf][loader]") {
  tinygltf::Model model = parse("attributes.gltf");
  auto uv = [&](const char* name) {
    return pt::gltf::read_texcoords(model, attribute(model, 0, name), 3, "attributes.gltf", name);
  };
  std::vector<glm::vec2> f = uv("TEXCOORD_0"), u8 = uv("TEXCOORD_1"), u16 = uv("TEXCOORD_2");
  std::vector<glm::vec2> sparse = uv("TEXCOORD_3");
  REQUIRE(f.size() == 3);
  check_uv(f[0], {0.5f, 1.5f});
  check_uv(f[1], {-1.0f, 2.0f});
  check_uv(f[2], {0.25f, 0.0f});
  check_uv(u8[0], {0.0f, 1.0f});  // bytes 0, 255 (elements padded to 4 bytes)
  check_uv(u8[1], {0.2f, 0.4f});  // 51 / 255, 102 / 255
  check_uv(u8[2], {1.0f, 0.0f});
  check_uv(u16[0], {0.0f, 1.0f});
  check_uv(u16[1], {0.2f, 32768.0f / 65535.0f});
  check_uv(u16[2], {1.0f, 0.0f});
  check_uv(sparse[0], f[0]);  // TEXCOORD_0's data with element 1 replaced
  check_uv(sparse[1], {7.0f, 8.0f});
  check_uv(sparse[2], f[2]);
}

TEST_CASE("colours VEC3 and VEC4 of FLOAT, u8 and u16 read to known values; VEC3 is opaque",
          "[gltf][loader]") {
  tinygltf::Model model = parse("attributes.gltf");
  auto colors = [&](int primitive, const char* name) {
    return pt::gltf::read_colors(model, attribute(model, primitive, name), 3, "attributes.gltf", name);
  };
  std::vector<glm::vec4> rgb = colors(0, "COLOR_0"), rgba_u8 = colors(1, "COLOR_0");
  std::vector<glm::vec4> rgba_u16 = colors(1, "COLOR_1"), rgb_u8 = colors(1, "COLOR_2");
  check_color(rgb[0], {1, 0, 0, 1});
  check_color(rgb[2], {0, 0, 0.5f, 1});
  check_color(rgba_u8[0], {1, 0, 0, 1});
  check_color(rgba_u8[1], {0, 0.2f, 0, 0.4f});
  check_color(rgba_u8[2], {0, 0, 1, 0});
  check_color(rgba_u16[1], {0, 0.2f, 0, 0});
  check_color(rgba_u16[2], {0, 0, 1, 32768.0f / 65535.0f});
  check_color(rgb_u8[0], {1, 0, 0.2f, 1});
  check_color(rgb_u8[2], {0, 0, 1, 1});
}

TEST_CASE("texture coordinates and colours that the spec does not allow are errors", "[gltf][loader]") {
  tinygltf::Model model = parse("attributes.gltf");
  int uv_float = attribute(model, 0, "TEXCOORD_0"), uv_u8 = attribute(model, 0, "TEXCOORD_1");
  int rgb = attribute(model, 0, "COLOR_0");
  const std::string file = "attributes.gltf";
  SECTION("count other than the vertex count") {
    require_refusal([&] { pt::gltf::read_texcoords(model, uv_float, 4, file, "TEXCOORD_0"); },
                    {"attributes.gltf: TEXCOORD_0", "has 3 entries, POSITION has 4"});
  }
  SECTION("u8 without normalized") {
    model.accessors[uv_u8].normalized = false;
    require_refusal([&] { pt::gltf::read_texcoords(model, uv_u8, 3, file, "TEXCOORD_1"); },
                    {"TEXCOORD_1 must be VEC2 of FLOAT", "normalized true", "componentType 5121"});
  }
  SECTION("a colour read as texture coordinates, and the reverse") {
    require_refusal([&] { pt::gltf::read_texcoords(model, rgb, 3, file, "COLOR_0"); }, {"must be VEC2"});
    require_refusal([&] { pt::gltf::read_colors(model, uv_float, 3, file, "TEXCOORD_0"); },
                    {"must be VEC3 or VEC4"});
  }
  SECTION("a non-finite value") {
    const tinygltf::Accessor& a = model.accessors[uv_float];
    const tinygltf::BufferView& v = model.bufferViews[a.bufferView];
    float nan = std::numeric_limits<float>::quiet_NaN();
    std::memcpy(&model.buffers[v.buffer].data[v.byteOffset + a.byteOffset + 12], &nan, 4);  // entry 1, v
    require_refusal([&] { pt::gltf::read_texcoords(model, uv_float, 3, file, "TEXCOORD_0"); },
                    {"TEXCOORD_0 entry 1 is not finite"});
  }
}

// --- Required extensions and Git LFS pointers, before any buffer is read ---------------------

TEST_CASE("a required extension the renderer does not read is named with the way out", "[gltf][loader]") {
  // no accessor of the Draco file has a bufferView: tinygltf would have called it malformed
  require_bad_scene(fixture("required_draco.gltf"),
                    {"extensionsRequired lists KHR_draco_mesh_compression", "gltf-transform copy"});
  require_bad_scene(fixture("required_meshopt.gltf"),
                    {"extensionsRequired lists EXT_meshopt_compression", "gltfpack"});
  require_bad_scene(fixture("required_quantization.gltf"),
                    {"extensionsRequired lists KHR_mesh_quantization", "dequantize"});
  require_bad_scene(fixture("required_basisu.gltf"),
                    {"extensionsRequired lists KHR_texture_basisu", "PNG or JPEG"});
  require_bad_scene(fixture("required_webp.gltf"),
                    {"extensionsRequired lists EXT_texture_webp", "PNG or JPEG"});
  require_bad_scene(fixture("required_unknown.gltf"), {"extensionsRequired lists EXT_made_up_extension",
                                                       "does not support", "KHR_texture_transform"});
}

TEST_CASE("KHR_texture_transform may be required", "[gltf][loader]") {
  CHECK(load("required_texture_transform.gltf").triangles.size() == 1);
}

TEST_CASE("a Git LFS pointer in place of the scene is named as one", "[gltf][loader]") {
  for (const char* name : {"lfs_pointer.gltf", "lfs_pointer.glb"}) {
    INFO(name);
    require_bad_scene(fixture(name),
                      {name, ": is a Git LFS pointer, not the glTF file itself", "git lfs pull"});
  }
}

TEST_CASE("a Git LFS pointer in place of an external buffer is named as one", "[gltf][loader]") {
  require_bad_scene(
      fixture("lfs_buffer.gltf"),
      {"lfs_buffer.gltf:", "buffers[0].uri 'lfs_buffer.bin' is a Git LFS pointer", "git lfs pull"});
}

TEST_CASE("a Git LFS pointer in place of an image file is named as one", "[gltf][loader][texture]") {
  require_bad_scene(fixture("tex_lfs.gltf"), {"tex_lfs.gltf:", "images[0]", "is a Git LFS pointer, not the image itself",
                                              "git lfs pull"});
}
