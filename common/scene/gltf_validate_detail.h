// Helpers shared by the glTF checks (gltf_precheck.cpp, gltf_validate.cpp, gltf_elements.cpp
// and gltf_accessors.cpp): the extensions the renderer reads, numbers and byte counts in
// messages, little-endian reads, and the range check of an index into one of the file's arrays.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <set>
#include <string>

#include "common/scene/gltf_validate.h"

namespace pt::gltf::detail {

// The extensions this renderer reads: the one list. gltf_precheck.cpp refuses any other in
// extensionsRequired; gltf_validate.cpp names the others in extensionsUsed once.
inline const std::set<std::string> kSupportedExtensions = {"EXT_mesh_gpu_instancing", "KHR_materials_emissive_strength",
                                                           "KHR_materials_transmission", "KHR_materials_ior",
                                                           "KHR_materials_specular",
                                                           "KHR_lights_punctual", "KHR_texture_transform"};

// "A, B, C" for messages.
inline std::string supported_extensions_text() {
  std::string text;
  for (const std::string& name : kSupportedExtensions) text += (text.empty() ? "" : ", ") + name;
  return text;
}

inline std::string str(std::uint64_t n) { return std::to_string(n); }

// A clone without `git lfs pull` holds small text files in place of the real ones: the
// scene, its buffers and its images are each checked for this first line.
inline constexpr char kLfsPointer[] = "version https://git-lfs.github.com/spec/v1";
inline const std::string kLfsAdvice = "run `git lfs pull` in its repository (or download the real file)";

inline bool is_lfs_pointer(const unsigned char* bytes, std::size_t size) {
  const std::size_t n = sizeof kLfsPointer - 1;
  return size >= n && std::memcmp(bytes, kLfsPointer, n) == 0;
}

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
