// Test support for the texture tests (tests/common/kernel/test_texture.cpp,
// tests/common/scene/test_gltf_textures.cpp, test_gltf_images.cpp, test_texture_scene.cpp,
// tests/stages/test_texture_images.cpp, test_texture_emissive_alpha.cpp): a texel packed as
// the texture table stores it (8-bit RGBA, R in the low byte; scene_types.h Texture).
#pragma once

#include <cstdint>

namespace pt_test {

inline std::uint32_t rgba(std::uint32_t r, std::uint32_t g, std::uint32_t b, std::uint32_t a) {
  return r | g << 8 | b << 16 | a << 24;
}

}  // namespace pt_test
