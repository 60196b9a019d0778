// The CPU's specialised kernels (issue "model only what a scene requires"): the GPU
// specialises a stage's kernel to the exact feature set of the scene when it makes the
// pipeline, but C++ is compiled ahead of time, so each stage is compiled a few times, once
// per combination of the coarse feature groups below that its code depends on
// (cmake/PtStage.cmake), and a render takes the smallest copy that covers its scene.
#pragma once

#include <cstddef>

#include "common/kernel/scene_types.h"

namespace pt {

// Always compiled in: triangles, the diffuse lobe, emissive triangles (the Cornell box).
constexpr uint kCpuBaseFeatures = kFeatureTriangles | kFeatureDiffuse | kFeatureTriangleLights;

// The groups a variant switches, in the order of the variant index's bits.
constexpr uint kCpuFeatureGroups[] = {
    kFeatureSpheres | kFeatureSphereLights,  // bit 0: spheres
    kFeatureMirror | kFeatureGlass,          // bit 1: delta lobes
    kFeatureConductor | kFeatureMixed | kFeatureTextures | kFeatureAlphaMask | kFeatureDielectric |
        kFeatureShadingNormals,              // bit 2: GGX, mixed, textures, glTF's dielectric, shading normals
    kFeaturePointLights | kFeatureSky,       // bit 3: lights other than area lights
};
constexpr unsigned kCpuFeatureGroupCount = sizeof kCpuFeatureGroups / sizeof kCpuFeatureGroups[0];

// The features of variant `index` of a stage compiled in `count` variants (a power of 2):
// the groups beyond the stage's first log2(count) are always on.
constexpr uint cpu_variant_features(unsigned index, unsigned count) {
  uint features = kCpuBaseFeatures;
  for (unsigned g = 0; g < kCpuFeatureGroupCount; g++) {
    bool switched = (1u << g) < count;
    if (!switched || (index >> g & 1u)) features |= kCpuFeatureGroups[g];
  }
  return features;
}

// The smallest variant of `count` whose features include `features`.
constexpr unsigned cpu_variant_index(uint features, unsigned count) {
  unsigned index = 0;
  for (unsigned g = 0; g < kCpuFeatureGroupCount && (1u << g) < count; g++) {
    if (features & kCpuFeatureGroups[g]) index |= 1u << g;
  }
  return index;
}

static_assert(cpu_variant_features(0, 1) == kFeatureAll);
static_assert(cpu_variant_features(15, 16) == kFeatureAll);
static_assert(cpu_variant_index(kFeatureAll, 16) == 15);

}  // namespace pt

// Inside a stage's CPU kernel compiled as variant PT_CPU_VARIANT (cmake/PtStage.cmake):
// the kernel's features (features.glsl) and the namespace of this copy.
#ifdef PT_CPU_VARIANT
#define PT_CPU_FEATURES (pt::cpu_variant_features(PT_CPU_VARIANT, PT_CPU_VARIANT_COUNT))
#define PT_CPU_CONCAT2(a, b) a##b
#define PT_CPU_CONCAT(a, b) PT_CPU_CONCAT2(a, b)
#define PT_CPU_VARIANT_NS PT_CPU_CONCAT(v, PT_CPU_VARIANT)
#endif
