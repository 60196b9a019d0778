// The accessors a primitive reads (POSITION, indices, TEXCOORD_n, COLOR_n, and
// EXT_mesh_gpu_instancing's attributes), for the glTF loader of the contract (README.md)
// "Scenes". Every read goes through read_elements (gltf_elements.h), which checks the
// accessor and applies its sparse substitutions; the readers here decode what it yields.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "common/scene/gltf_elements.h"
#include "common/scene/gltf_validate.h"
#include "common/scene/gltf_validate_detail.h"

namespace pt::gltf {

using namespace detail;

namespace {

// The components of a TEXCOORD_n or COLOR_n accessor as floats, `components` per vertex
// (0: its type is not one of `shapes`). The glTF 2.0 table of mesh attributes allows
// FLOAT, and UNSIGNED_BYTE or UNSIGNED_SHORT with normalized set (c / 255, c / 65535).
// EXT_mesh_gpu_instancing's attributes (instances: true) allow FLOAT, and its ROTATION BYTE or
// SHORT with normalized set (max(c / 127, -1), max(c / 32767, -1)), one per instance.
std::vector<float> read_attribute_floats(const tinygltf::Model& model, int accessor, int components,
                                         std::size_t vertex_count, const std::string& file,
                                         const std::string& what, const std::string& shapes, bool instances = false) {
  const tinygltf::Accessor& a = accessor_at(model, accessor, file, what);
  bool is_float = a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
  bool is_signed = instances && components == 4 &&
                   (a.componentType == TINYGLTF_COMPONENT_TYPE_BYTE || a.componentType == TINYGLTF_COMPONENT_TYPE_SHORT);
  std::size_t size = is_float    ? 4
                     : is_signed ? (a.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ? 1 : 2)
                     : instances ? 0
                     : a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE  ? 1
                     : a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                                                                                 : 0;
  if (components == 0 || size == 0 || (!is_float && !a.normalized)) {
    fail(file, what + " must be " + shapes +
                   (instances ? " of FLOAT (ROTATION: or of BYTE or SHORT with normalized true)"
                              : " of FLOAT, or of UNSIGNED_BYTE or UNSIGNED_SHORT with normalized true") +
                   " (type " + std::to_string(a.type) + ", componentType " + std::to_string(a.componentType) +
                   (a.normalized ? ", normalized" : "") + "): " + kReexport);
  }
  if (a.count != vertex_count) {
    fail(file, what + " has " + str(a.count) + " entries, " +
                   (instances ? "the node's first instancing attribute has " + str(vertex_count) +
                                    "; each has one per instance: "
                              : "POSITION has " + str(vertex_count) + "; an attribute has one per vertex: ") +
                   kReexport);
  }
  Elements elements = read_elements(model, accessor, size * components, file, what);
  std::vector<float> values(elements.count * components);
  for (std::size_t i = 0; i < elements.count; ++i) {
    for (int c = 0; c < components; ++c) {
      const unsigned char* p = elements.at(i) + c * size;
      float& v = values[i * components + c];
      if (is_float) {
        std::memcpy(&v, p, 4);
      } else {
        v = is_signed ? std::max(float(std::int16_t(size == 1 ? std::int8_t(p[0]) : read_unsigned(p, 2))) /
                                     (size == 1 ? 127.0f : 32767.0f),
                                 -1.0f)
                      : float(read_unsigned(p, size)) / (size == 1 ? 255.0f : 65535.0f);
      }
      if (!std::isfinite(v)) {
        fail(file, what + " entry " + str(i) + " is not finite (" + std::to_string(v) + "): " + kReexport);
      }
    }
  }
  return values;
}

}  // namespace

std::vector<glm::vec3> read_positions(const tinygltf::Model& model, int accessor, const std::string& file,
                                      const std::string& what) {
  const tinygltf::Accessor& a = accessor_at(model, accessor, file, what);
  if (a.type != TINYGLTF_TYPE_VEC3 || a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
    fail(file, what + " must be VEC3 of FLOAT (type " + std::to_string(a.type) + ", componentType " +
                   std::to_string(a.componentType) + "): re-export without mesh quantization");
  }
  Elements elements = read_elements(model, accessor, 12, file, what);
  std::vector<glm::vec3> positions(elements.count);
  for (std::size_t i = 0; i < elements.count; ++i) {
    std::memcpy(&positions[i], elements.at(i), 12);
    const glm::vec3& p = positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      fail(file, what + " vertex " + str(i) + " is not finite (" + std::to_string(p.x) + ", " +
                     std::to_string(p.y) + ", " + std::to_string(p.z) + "): " + kReexport);
    }
  }
  return positions;
}

std::vector<std::uint32_t> read_indices(const tinygltf::Model& model, int accessor, std::size_t vertex_count,
                                        const std::string& file, const std::string& what) {
  const tinygltf::Accessor& a = accessor_at(model, accessor, file, what);
  std::size_t size = unsigned_size(a.componentType);
  if (a.type != TINYGLTF_TYPE_SCALAR || size == 0) {
    fail(file, what + " must be SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT: " +
                   std::string(kReexport));
  }
  Elements elements = read_elements(model, accessor, size, file, what);
  std::vector<std::uint32_t> indices(elements.count);
  for (std::size_t i = 0; i < elements.count; ++i) {
    std::uint32_t index = read_unsigned(elements.at(i), size);
    if (index >= vertex_count) {
      fail(file, what + " entry " + str(i) + " is " + str(index) + ", past the vertex count (" +
                     str(vertex_count) + "): " + kReexport);
    }
    indices[i] = index;
  }
  return indices;
}

std::vector<glm::vec2> read_texcoords(const tinygltf::Model& model, int accessor, std::size_t vertex_count,
                                      const std::string& file, const std::string& what) {
  int components = accessor_at(model, accessor, file, what).type == TINYGLTF_TYPE_VEC2 ? 2 : 0;
  std::vector<float> f = read_attribute_floats(model, accessor, components, vertex_count, file, what, "VEC2");
  std::vector<glm::vec2> uv(vertex_count);
  for (std::size_t i = 0; i < vertex_count; ++i) uv[i] = glm::vec2(f[2 * i], f[2 * i + 1]);
  return uv;
}

std::vector<glm::vec4> read_colors(const tinygltf::Model& model, int accessor, std::size_t vertex_count,
                                   const std::string& file, const std::string& what) {
  int type = accessor_at(model, accessor, file, what).type;
  int components = type == TINYGLTF_TYPE_VEC3 ? 3 : type == TINYGLTF_TYPE_VEC4 ? 4 : 0;
  std::vector<float> f =
      read_attribute_floats(model, accessor, components, vertex_count, file, what, "VEC3 or VEC4");
  std::vector<glm::vec4> colors(vertex_count);
  for (std::size_t i = 0; i < vertex_count; ++i) {
    const float* c = &f[i * components];
    colors[i] = glm::vec4(c[0], c[1], c[2], components == 4 ? c[3] : 1.0f);  // VEC3: opaque
  }
  return colors;
}

std::vector<float> read_instance_attribute(const tinygltf::Model& model, int accessor, int components,
                                           std::size_t instances, const std::string& file, const std::string& what) {
  const bool ok = accessor_at(model, accessor, file, what).type == (components == 4 ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3);
  return read_attribute_floats(model, accessor, ok ? components : 0, instances, file, what,
                               components == 4 ? "VEC4" : "VEC3", true);
}

}  // namespace pt::gltf
