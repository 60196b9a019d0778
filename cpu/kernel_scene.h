// A stage's kernel compiled as C++, as the CPU backend calls it: the scene's arrays as the
// kernel sees them (KernelScene, bound to the globals of kernel_bindings.h by kernel_entry.h),
// and the kernel's two entry points (CpuKernel). The GPU's counterpart is the buffers of
// gpu/kernel_bindings.glsl. Not part of the article: the machinery of the CPU backend.
#pragma once

#include <glm/glm.hpp>

#include "common/kernel/scene_types.h"

namespace pt {

struct WideBvh;  // the CPU backend's own form of the BVH (cpu/wide_bvh.h)

// The scene arrays as the CPU kernel sees them (cpu/kernel_bindings.h; the GLSL buffers of gpu/kernel_bindings.glsl).
struct KernelScene {
  const Triangle* triangles;
  const Sphere* spheres;
  const Material* materials;
  const PointLight* point_lights;
  uint* counters;  // kCounterCount values, updated by the kernel
  const Light* lights;
  const LightAlias* light_alias = nullptr;  // the light table's alias table (scene.h light_alias)
  const LightRun* light_runs = nullptr;     // its triangle lights as runs (scene.h light_runs)
  uint light_run_count = 0;
  uint triangle_light_count = 0;            // the lights the runs cover
  const float* triangle_soa = nullptr;  // the triangles as arrays (triangle_soa.h), or nullptr
  uint triangle_soa_stride = 0;
  const float* sphere_soa = nullptr;  // the spheres as arrays (cpu/sphere_soa.h), or nullptr
  uint sphere_soa_stride = 0;
  uint sphere_soa_count = 0;
  const BvhNode* bvh_nodes = nullptr;  // the BVH (common/scene/bvh.h), or nullptr
  const uint* bvh_indices = nullptr;
  const WideBvh* wide_bvh = nullptr;   // the same tree for the CPU's SIMD walk, or nullptr
  // Textures and vertex colours (common/kernel/texture.glsl), or nullptr without them.
  const TriangleAttributes* triangle_attributes = nullptr;
  const MaterialTextures* material_textures = nullptr;
  const Texture* textures = nullptr;
  const uint* texels = nullptr;
  const TriangleShading* triangle_shading = nullptr;  // shading normals, or nullptr without them
  const float* environment_radiance = nullptr;  // the environment map (common/scene/environment.h),
  const float* environment_tables = nullptr;    // or nullptr without one
  // The features the render asked for (the scene's, or every one with --all-features): read
  // by a copy of the kernel built with PT_CPU_RUNTIME_FEATURES (kernel_bindings.h) only.
  uint features = kFeatureAll;
};

// A stage's kernel compiled as C++ (cpu/kernel_entry.h): one copy per feature variant
// (cpu/cpu_variants.h), listed in StageKernels::cpu (common/render/backend.h).
struct CpuKernel {
  void (*bind)(const KernelScene& scene, const FrameParams& pass);
  void (*render_rows)(uint y0, uint y1, glm::vec4* out);
};

}  // namespace pt
