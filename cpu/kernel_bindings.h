// The CPU side of the kernel's view of the scene: the flat arrays of
// common/kernel/scene_types.h and the per-pass parameters as plain globals (set by
// kernel_entry.h before each pass), and the kernel's feature set as a compile-time constant.
// gpu/kernel_bindings.glsl declares the same names as Vulkan buffers. Included inside a
// kernel's namespace (kernel_begin.h).
#ifndef PT_CPU_KERNEL_BINDINGS_H
#define PT_CPU_KERNEL_BINDINGS_H

inline const Triangle* triangles = nullptr;
inline const Sphere* spheres = nullptr;
inline const Material* materials = nullptr;
inline const PointLight* point_lights = nullptr;
inline FrameParams params;
inline uint* counters = nullptr;       // kCounterCount event counters, updated atomically
inline const Light* lights = nullptr;  // the light table (stage4)
inline const LightAlias* light_alias = nullptr;  // its alias table (lights.glsl pick_light_entry)
inline LightAlias light_alias_at(uint i) { return light_alias[i]; }
// The triangle lights as runs of consecutive triangles (scene.h light_runs), or none.
inline const LightRun* light_runs = nullptr;
inline uint light_run_count = 0u;
inline uint triangle_light_count = 0u;
// A hint to the memory, no more (lights.glsl pick_light_entry): the triangle of light
// `light`, which a pick in its cell most often samples, fetched while the cell itself is
// read, so that the two cache misses overlap instead of following one another. The runs
// give the triangle without reading the light table; a light they do not cover gets none.
inline void prefetch_light_triangle(uint light) {
  if (light >= triangle_light_count) return;
  uint lo = 0u, hi = light_run_count;  // the last run that starts at or before `light`
  while (hi - lo > 1u) {
    const uint mid = (lo + hi) / 2u;
    if (light_runs[mid].first_light <= light) lo = mid;
    else hi = mid;
  }
  const char* t = reinterpret_cast<const char*>(&triangles[light_runs[lo].first_triangle + (light - light_runs[lo].first_light)]);
  __builtin_prefetch(t), __builtin_prefetch(t + sizeof(Triangle) - 1);
}
inline thread_local uint rng_state = 0u;  // the random-number state of one invocation
inline thread_local uvec4 sampler_state = uvec4(0u);  // the sampler's (common/kernel/sampler.glsl)
// The triangles again as a structure of arrays for the SIMD search (triangle_lanes.h,
// triangle_soa.h): nullptr means the plain loop over triangles[].
inline const float* triangle_soa = nullptr;
inline uint triangle_soa_stride = 0u;  // floats per array (the padded triangle count)
// The spheres as arrays for the SIMD test (sphere_lanes.h, sphere_soa.h): nullptr means the
// plain loop over spheres[].
inline const float* sphere_soa = nullptr;
inline uint sphere_soa_stride = 0u;  // floats per array (the padded sphere count)
inline uint sphere_soa_count = 0u;   // the spheres
// The BVH over the triangles (common/scene/bvh.h, walked by common/kernel/bvh.glsl):
// nullptr when the render has none (--accel none, or no triangles).
inline const BvhNode* bvh_nodes = nullptr;
inline const uint* bvh_indices = nullptr;
// The same tree collapsed for the CPU's SIMD walk (cpu/wide_bvh.h), which replaces the
// binary walk when set: nullptr when the binding had none (tests, the double-precision build).
inline const pt::WideBvh* wide_bvh = nullptr;
// Textures and vertex colours (common/kernel/texture.glsl): nullptr when the scene has none.
inline const TriangleAttributes* triangle_attributes = nullptr;  // parallel to triangles[]
inline const MaterialTextures* material_textures = nullptr;      // parallel to materials[]
inline const Texture* textures = nullptr;                        // the texture table
inline const uint* texels = nullptr;                             // 8-bit RGBA texels
// Shading normals (common/kernel/shading_normal.glsl): nullptr when the scene has none.
inline const TriangleShading* triangle_shading = nullptr;        // parallel to triangles[]
// The environment map (common/kernel/environment.glsl): nullptr when the scene has none.
inline const float* env_texels = nullptr;  // RGB per texel
inline const float* env_tables = nullptr;  // the sampling distribution's tables
inline vec3 environment_texel(uint i) {
  return vec3(env_texels[3u * i], env_texels[3u * i + 1u], env_texels[3u * i + 2u]);
}
inline float environment_table(uint i) { return env_tables[i]; }
inline Triangle triangle_at(uint i) { return triangles[i]; }
// The BVH's nodes as bvh.glsl reads them (gpu/kernel_bindings.glsl reads them as texels).
inline BvhNode bvh_node_at(uint i) { return bvh_nodes[i]; }
inline uint bvh_index_at(uint i) { return bvh_indices[i]; }

// The features this copy of the kernel is compiled for (cpu_variants.h): one copy per
// variant, so the code of a feature the scene lacks is not in the copy that renders it.
// PT_CPU_RUNTIME_FEATURES (the check build's one copy per stage, cmake/Labs.cmake):
// the render's feature set read at run time (KernelScene::features), as the GPU's
// specialization constant gives it, so that has_feature() decides at every bit of the mask
// exactly as a GPU kernel specialised to the scene does; tests/stages/test_specialised.cpp
// then checks the shared code's gates for each scene of it on the CPU.
#if defined(PT_CPU_RUNTIME_FEATURES)
inline uint kSceneFeatures = kFeatureAll;
#elif defined(PT_CPU_FEATURES)
const uint kSceneFeatures = PT_CPU_FEATURES;
#else
const uint kSceneFeatures = kFeatureAll;
#endif

#include "common/kernel/features.glsl"

#endif  // PT_CPU_KERNEL_BINDINGS_H
