// The accessors a triangle primitive reads (POSITION and indices), for the glTF loader of
// the contract (README.md) "Scenes": each checked against its bufferView and buffer, with
// every size added and multiplied under overflow checks, then read element by element.
#include <cmath>
#include <cstring>

#include "common/scene/gltf_validate.h"
#include "common/scene/gltf_validate_detail.h"

namespace pt::gltf {

using namespace detail;

namespace {

struct AccessorData {
  const unsigned char* first;  // the first element
  std::size_t stride;          // bytes from one element to the next
  std::size_t count;
};

// Checks an accessor against its bufferView and the bufferView against its buffer.
AccessorData locate(const tinygltf::Model& model, int index, std::size_t element_size,
                    const std::string& file, const std::string& what) {
  check_index(file, index, model.accessors.size(), what, "accessors");
  const tinygltf::Accessor& a = model.accessors[index];
  if (a.sparse.isSparse)
    fail(file, what + " is sparse; sparse accessors are not supported: re-export without them");
  if (a.count == 0) fail(file, what + " has count 0; a primitive needs vertices: " + std::string(kReexport));
  if (a.bufferView < 0) fail(file, what + " has no bufferView (no data): " + std::string(kReexport));
  check_index(file, a.bufferView, model.bufferViews.size(), what + ".bufferView", "bufferViews");
  const tinygltf::BufferView& v = model.bufferViews[a.bufferView];
  std::string view = "bufferViews[" + std::to_string(a.bufferView) + "]";
  check_index(file, v.buffer, model.buffers.size(), view + ".buffer", "buffers");
  std::uint64_t view_end = 0, has = model.buffers[v.buffer].data.size();
  bool overflow = __builtin_add_overflow(std::uint64_t(v.byteOffset), std::uint64_t(v.byteLength), &view_end);
  if (overflow || view_end > has) {
    fail(file, view + " (used by " + what + ") runs past buffers[" + std::to_string(v.buffer) + "] (" +
                   need_text(overflow, view_end, has) + "): " + kReexport);
  }
  std::size_t stride = v.byteStride != 0 ? v.byteStride : element_size;
  if (stride < element_size) {
    fail(file, view + ".byteStride " + str(stride) + " is smaller than an element of " + what + " (" +
                   str(element_size) + " bytes): " + kReexport);
  }
  std::uint64_t needed = 0;  // byteOffset + stride * (count - 1) + element size
  overflow = __builtin_mul_overflow(std::uint64_t(stride), std::uint64_t(a.count - 1), &needed) ||
             __builtin_add_overflow(needed, std::uint64_t(a.byteOffset), &needed) ||
             __builtin_add_overflow(needed, std::uint64_t(element_size), &needed);
  if (overflow || needed > v.byteLength) {
    fail(file,
         what + " runs past " + view + " (" + need_text(overflow, needed, v.byteLength) + "): " + kReexport);
  }
  return {model.buffers[v.buffer].data.data() + v.byteOffset + a.byteOffset, stride, a.count};
}

}  // namespace

std::vector<glm::vec3> read_positions(const tinygltf::Model& model, int accessor, const std::string& file,
                                      const std::string& what) {
  check_index(file, accessor, model.accessors.size(), what, "accessors");
  const tinygltf::Accessor& a = model.accessors[accessor];
  if (a.type != TINYGLTF_TYPE_VEC3 || a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
    fail(file, what + " must be VEC3 of FLOAT (type " + std::to_string(a.type) + ", componentType " +
                   std::to_string(a.componentType) + "): re-export without mesh quantization");
  }
  AccessorData data = locate(model, accessor, 12, file, what);
  std::vector<glm::vec3> positions(data.count);
  for (std::size_t i = 0; i < data.count; ++i) {
    std::memcpy(&positions[i], data.first + i * data.stride, 12);
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
  check_index(file, accessor, model.accessors.size(), what, "accessors");
  const tinygltf::Accessor& a = model.accessors[accessor];
  std::size_t size = a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 1
                     : a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                     : a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT   ? 4
                                                                                 : 0;
  if (a.type != TINYGLTF_TYPE_SCALAR || size == 0) {
    fail(file, what + " must be SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT: " +
                   std::string(kReexport));
  }
  AccessorData data = locate(model, accessor, size, file, what);
  std::vector<std::uint32_t> indices(data.count);
  for (std::size_t i = 0; i < data.count; ++i) {
    const unsigned char* p = data.first + i * data.stride;
    std::uint32_t index = size == 1 ? p[0] : size == 2 ? std::uint32_t(p[0] | p[1] << 8) : read_u32_le(p);
    if (index >= vertex_count) {
      fail(file, what + " entry " + str(i) + " is " + str(index) + ", past the vertex count (" +
                     str(vertex_count) + "): " + kReexport);
    }
    indices[i] = index;
  }
  return indices;
}

}  // namespace pt::gltf
