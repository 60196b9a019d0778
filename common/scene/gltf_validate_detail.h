// Helpers shared by the glTF checks (gltf_precheck.cpp, gltf_validate.cpp and
// gltf_accessors.cpp): numbers and byte counts in messages, little-endian reads, and the
// range check of an index into one of the file's arrays.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "common/scene/gltf_validate.h"

namespace pt::gltf::detail {

inline std::string str(std::uint64_t n) { return std::to_string(n); }

// "needs N bytes, has M", or the overflow that prevents saying N.
inline std::string need_text(bool overflowed, std::uint64_t needed, std::uint64_t has) {
  if (overflowed) return "its offsets overflow 64 bits, has " + str(has) + " bytes";
  return "needs " + str(needed) + " bytes, has " + str(has);
}

inline std::uint32_t read_u32_le(const unsigned char* p) {
  return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 |
         std::uint32_t(p[3]) << 24;
}

// Fails unless 0 <= index < size; `where` is the index's JSON path, `array` what it indexes.
inline void check_index(const std::string& file, int index, std::size_t size, const std::string& where,
                        const char* array) {
  if (index < 0 || std::size_t(index) >= size) {
    fail(file, where + " = " + std::to_string(index) + " is out of range (" + array + " has " + str(size) +
                   (size == 1 ? " entry): " : " entries): ") + kReexport);
  }
}

}  // namespace pt::gltf::detail
