// An accessor's elements read safely, for the glTF loader of the contract (README.md)
// "Scenes": the accessor checked against its bufferView and the bufferView against its
// buffer, with every size added and multiplied under overflow checks, then glTF 2.0's sparse
// substitutions applied (gltf_elements.cpp). gltf_accessors.cpp decodes what they yield.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "common/scene/gltf_validate_detail.h"

namespace pt::gltf::detail {

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

// The accessor `index`, checked to exist; `what` names what reads it.
const tinygltf::Accessor& accessor_at(const tinygltf::Model& model, int index, const std::string& file,
                                      const std::string& what);

// Bytes of an UNSIGNED_BYTE / UNSIGNED_SHORT / UNSIGNED_INT component; 0 for other types.
inline std::size_t unsigned_size(int component_type) {
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

// An unsigned component of `size` bytes (unsigned_size), little-endian.
inline std::uint32_t read_unsigned(const unsigned char* p, std::size_t size) {
  return size == 1 ? p[0] : size == 2 ? std::uint32_t(p[0] | p[1] << 8) : read_u32_le(p);
}

// The one way every accessor is read: `count` elements of `element_size` bytes each.
Elements read_elements(const tinygltf::Model& model, int index, std::size_t element_size,
                       const std::string& file, const std::string& what);

}  // namespace pt::gltf::detail
