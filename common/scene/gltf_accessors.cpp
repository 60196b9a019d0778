// The accessors a primitive reads (POSITION, indices, TEXCOORD_n, COLOR_n), for the glTF
// loader of the contract (README.md) "Scenes". Every read goes through read_elements: the
// accessor checked against its bufferView and the bufferView against its buffer, with every
// size added and multiplied under overflow checks, then glTF 2.0's sparse substitutions
// applied; the readers decode the elements it yields.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "common/scene/gltf_validate.h"
#include "common/scene/gltf_validate_detail.h"

namespace pt::gltf {

using namespace detail;

namespace {

// A sparse accessor without a bufferView starts as zeros that the file only states the
// count of: a few bytes of JSON must not ask for gigabytes.
constexpr std::uint64_t kMaxZeroFill = std::uint64_t(1) << 28;  // 256 MiB

// An accessor's elements: in place in their buffer, or copied out and packed when sparse
// substitutions apply (then `first` is unused and `stride` is the element size).
struct Elements {
  const unsigned char* first = nullptr;
  std::size_t stride = 0;  // bytes from one element to the next
  std::size_t count = 0;
  std::vector<unsigned char> packed;

  const unsigned char* at(std::size_t i) const {
    return (packed.empty() ? first : packed.data()) + i * stride;
  }
};

const tinygltf::Accessor& accessor_at(const tinygltf::Model& model, int index, const std::string& file,
                                      const std::string& what) {
  check_index(file, index, model.accessors.size(), what, "accessors");
  return model.accessors[index];
}

// Bytes of an UNSIGNED_BYTE / UNSIGNED_SHORT / UNSIGNED_INT component; 0 for other types.
std::size_t unsigned_size(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return 4;
    default:
      return 0;
  }
}

std::uint32_t read_unsigned(const unsigned char* p, std::size_t size) {
  return size == 1 ? p[0] : size == 2 ? std::uint32_t(p[0] | p[1] << 8) : read_u32_le(p);
}

// The bufferView `index` checked against its buffer; `user` names what reads it.
const tinygltf::BufferView& checked_view(const tinygltf::Model& model, int index, const std::string& file,
                                         const std::string& user) {
  check_index(file, index, model.bufferViews.size(), user + ".bufferView", "bufferViews");
  const tinygltf::BufferView& v = model.bufferViews[index];
  std::string view = "bufferViews[" + std::to_string(index) + "]";
  check_index(file, v.buffer, model.buffers.size(), view + ".buffer", "buffers");
  std::uint64_t view_end = 0, has = model.buffers[v.buffer].data.size();
  bool overflow = __builtin_add_overflow(std::uint64_t(v.byteOffset), std::uint64_t(v.byteLength), &view_end);
  if (overflow || view_end > has) {
    fail(file, view + " (used by " + user + ") runs past buffers[" + std::to_string(v.buffer) + "] (" +
                   need_text(overflow, view_end, has) + "): " + kReexport);
  }
  return v;
}

// Fails unless `count` elements of `size` bytes, `stride` apart from byteOffset `offset`,
// fit in the bufferView `view` that `user` reads.
void check_span(const tinygltf::BufferView& v, int view, std::uint64_t offset, std::uint64_t stride,
                std::uint64_t count, std::uint64_t size, const std::string& file, const std::string& user) {
  std::uint64_t needed = 0;  // offset + stride * (count - 1) + size
  bool overflow = __builtin_mul_overflow(stride, count - 1, &needed) ||
                  __builtin_add_overflow(needed, offset, &needed) ||
                  __builtin_add_overflow(needed, size, &needed);
  if (overflow || needed > v.byteLength) {
    fail(file, user + " runs past bufferViews[" + std::to_string(view) + "] (" +
                   need_text(overflow, needed, v.byteLength) + "): " + kReexport);
  }
}

const unsigned char* view_data(const tinygltf::Model& model, const tinygltf::BufferView& v) {
  return model.buffers[v.buffer].data.data() + v.byteOffset;
}

// The elements in the accessor's bufferView, read in place.
Elements dense_elements(const tinygltf::Model& model, const tinygltf::Accessor& a, std::size_t element_size,
                        const std::string& file, const std::string& what) {
  if (a.bufferView < 0) fail(file, what + " has no bufferView (no data): " + std::string(kReexport));
  const tinygltf::BufferView& v = checked_view(model, a.bufferView, file, what);
  std::size_t stride = v.byteStride != 0 ? v.byteStride : element_size;
  if (stride < element_size) {
    fail(file, "bufferViews[" + std::to_string(a.bufferView) + "].byteStride " + str(stride) +
                   " is smaller than an element of " + what + " (" + str(element_size) +
                   " bytes): " + kReexport);
  }
  check_span(v, a.bufferView, a.byteOffset, stride, a.count, element_size, file, what);
  return {view_data(model, v) + a.byteOffset, stride, a.count, {}};
}

// What a sparse accessor starts from: its bufferView's elements, or zeros without one.
std::vector<unsigned char> sparse_base(const tinygltf::Model& model, const tinygltf::Accessor& a,
                                       std::size_t element_size, const std::string& file,
                                       const std::string& what) {
  std::uint64_t bytes = 0;
  bool overflow = __builtin_mul_overflow(std::uint64_t(a.count), std::uint64_t(element_size), &bytes);
  if (a.bufferView < 0) {
    if (overflow || bytes > kMaxZeroFill) {
      fail(file, what + " is sparse without a bufferView and has count " + str(a.count) +
                     ", more zeros than this renderer fills in (256 MiB): re-export it with its data in a "
                     "bufferView");
    }
    return std::vector<unsigned char>(bytes, 0);
  }
  Elements dense = dense_elements(model, a, element_size, file, what);  // bounds count by the buffer
  std::vector<unsigned char> packed(bytes);
  for (std::size_t i = 0; i < a.count; ++i) std::memcpy(&packed[i * element_size], dense.at(i), element_size);
  return packed;
}

// One of the two arrays of a sparse accessor (`user` is "... sparse.indices" or "... sparse.values"):
// `count` elements of `size` bytes, tightly packed from byteOffset in their bufferView.
const unsigned char* sparse_array(const tinygltf::Model& model, int view, int offset, std::size_t size,
                                  std::size_t count, const std::string& file, const std::string& user) {
  const tinygltf::BufferView& v = checked_view(model, view, file, user);
  if (offset < 0) fail(file, user + ".byteOffset is negative: " + std::string(kReexport));
  check_span(v, view, std::uint64_t(offset), size, count, size, file, user);
  return view_data(model, v) + offset;
}

// glTF 2.0 "Sparse Accessors": sparse.count indices, strictly increasing and below the
// accessor's count, each naming the element that the value at the same position replaces.
void apply_sparse(const tinygltf::Model& model, const tinygltf::Accessor& a, std::size_t element_size,
                  std::vector<unsigned char>& packed, const std::string& file, const std::string& what) {
  const auto& sparse = a.sparse;
  if (sparse.count <= 0 || std::size_t(sparse.count) > a.count) {
    fail(file, what + " has sparse.count " + std::to_string(sparse.count) + "; it must be 1 to its count (" +
                   str(a.count) + "): " + kReexport);
  }
  std::size_t count = std::size_t(sparse.count), index_size = unsigned_size(sparse.indices.componentType);
  if (index_size == 0) {
    fail(file, what + " sparse.indices.componentType " + std::to_string(sparse.indices.componentType) +
                   " is not UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT: " + kReexport);
  }
  const unsigned char* indices = sparse_array(model, sparse.indices.bufferView, sparse.indices.byteOffset,
                                              index_size, count, file, what + " sparse.indices");
  const unsigned char* values = sparse_array(model, sparse.values.bufferView, sparse.values.byteOffset,
                                             element_size, count, file, what + " sparse.values");
  for (std::size_t k = 0; k < count; ++k) {
    std::uint32_t index = read_unsigned(indices + k * index_size, index_size);
    std::string entry = what + " sparse index " + str(k) + " is " + str(index);
    if (index >= a.count) fail(file, entry + ", past its count (" + str(a.count) + "): " + kReexport);
    std::uint32_t previous = k > 0 ? read_unsigned(indices + (k - 1) * index_size, index_size) : 0;
    if (k > 0 && index <= previous) {
      fail(file, entry + ", not above the one before it (" + str(previous) +
                     "); sparse indices must strictly increase: " + kReexport);
    }
    std::memcpy(&packed[std::size_t(index) * element_size], values + k * element_size, element_size);
  }
}

// The one way every accessor is read: `count` elements of `element_size` bytes each.
Elements read_elements(const tinygltf::Model& model, int index, std::size_t element_size,
                       const std::string& file, const std::string& what) {
  const tinygltf::Accessor& a = accessor_at(model, index, file, what);
  if (a.count == 0) fail(file, what + " has count 0; a primitive needs vertices: " + std::string(kReexport));
  if (!a.sparse.isSparse) return dense_elements(model, a, element_size, file, what);
  Elements elements{nullptr, element_size, a.count, sparse_base(model, a, element_size, file, what)};
  apply_sparse(model, a, element_size, elements.packed, file, what);
  return elements;
}

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
