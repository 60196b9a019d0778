// The GPU side of the kernel's view of the scene: the flat arrays of
// common/kernel/scene_types.h as storage buffers, the per-pass parameters as a uniform
// block, and the kernel's feature set as a specialization constant (set when the pipeline
// is made for a scene, so the driver removes the code of every feature the scene lacks).
// cpu/kernel_bindings.h declares the same names for the CPU. compute_pipeline.cpp makes
// the matching descriptor set layout.
#ifndef PT_GPU_KERNEL_BINDINGS_GLSL
#define PT_GPU_KERNEL_BINDINGS_GLSL

layout(std430, set = 0, binding = 0) readonly buffer TriangleBuffer { Triangle triangles[]; };
layout(std430, set = 0, binding = 1) readonly buffer SphereBuffer { Sphere spheres[]; };
layout(std430, set = 0, binding = 2) readonly buffer MaterialBuffer { Material materials[]; };
layout(std430, set = 0, binding = 3) readonly buffer PointLightBuffer { PointLight point_lights[]; };
layout(std140, set = 0, binding = 4) uniform ParamsBuffer { FrameParams params; };
layout(std430, set = 0, binding = 5) writeonly buffer OutputBuffer { vec4 pass_output[]; };
layout(std430, set = 0, binding = 6) buffer CounterBuffer { uint counters[]; };
layout(std430, set = 0, binding = 7) readonly buffer LightBuffer { Light lights[]; };
// The BVH over the triangles (common/scene/bvh.h, walked by gpu/bvh_walk.glsl); a
// placeholder when the render has none (then params.accel is kAccelNone). The nodes are read
// as texels of a uniform texel buffer, two uvec4 per BvhNode: lavapipe reads a storage buffer
// one invocation and one component at a time (see triangle_at below), a texel for all its
// invocations at once; on lavapipe that made the walk 20-30% faster (docs/acceleration.md).
layout(set = 0, binding = 9) uniform usamplerBuffer bvh_node_texels;
layout(std430, set = 0, binding = 10) readonly buffer BvhIndexBuffer { uint bvh_indices[]; };
BvhNode bvh_node_at(uint i) {
  uvec4 a = texelFetch(bvh_node_texels, int(2u * i));
  uvec4 b = texelFetch(bvh_node_texels, int(2u * i + 1u));
  return BvhNode(uintBitsToFloat(a.xyz), a.w, uintBitsToFloat(b.xyz), b.w);
}
uint bvh_index_at(uint i) { return bvh_indices[i]; }
// Textures and vertex colours (common/kernel/texture.glsl); placeholders when the scene
// has none (kFeatureTextures off).
layout(std430, set = 0, binding = 11) readonly buffer TriangleAttributeBuffer { TriangleAttributes triangle_attributes[]; };
layout(std430, set = 0, binding = 12) readonly buffer MaterialTextureBuffer { MaterialTextures material_textures[]; };
layout(std430, set = 0, binding = 13) readonly buffer TextureBuffer { Texture textures[]; };
layout(std430, set = 0, binding = 14) readonly buffer TexelBuffer { uint texels[]; };
// Shading normals (common/kernel/shading_normal.glsl); a placeholder without them.
layout(std430, set = 0, binding = 15) readonly buffer TriangleShadingBuffer { TriangleShading triangle_shading[]; };
// The environment map (common/kernel/environment.glsl); placeholders without one.
layout(std430, set = 0, binding = 16) readonly buffer EnvironmentRadianceBuffer { float env_texels[]; };
layout(std430, set = 0, binding = 17) readonly buffer EnvironmentTableBuffer { float env_tables[]; };
vec3 environment_texel(uint i) {
  return vec3(env_texels[3u * i], env_texels[3u * i + 1u], env_texels[3u * i + 2u]);
}
float environment_table(uint i) { return env_tables[i]; }
// The light table's alias table (common/kernel/lights.glsl pick_light_entry).
layout(std430, set = 0, binding = 18) readonly buffer LightAliasBuffer { LightAlias light_alias[]; };
LightAlias light_alias_at(uint i) { return light_alias[i]; }
// A hint the CPU gives its memory (cpu/kernel_bindings.h); a GPU hides the latency with
// other invocations instead.
void prefetch_light_triangle(uint light) {}
uint rng_state;  // the random-number state of one invocation
uvec4 sampler_state;  // the sampler's state of one invocation (common/kernel/sampler.glsl)

// The triangles again in a uniform buffer when the scene's fit in one (gpu_backend.cpp):
// lavapipe (Mesa's llvmpipe) reads a storage buffer lane by lane, a branch and a bounds
// test for every invocation and component, even at an index all invocations share, as the
// loop over the triangles has; from a uniform buffer such a read is one load for all.
// kUniformTriangles: how many the uniform copy can hold, 0 when it is not used (a
// specialization constant: the driver keeps only one of the two reads).
layout(constant_id = 1) const uint kUniformTriangles = 0u;
layout(std140, set = 0, binding = 8) uniform UniformTriangleBuffer { Triangle uniform_triangles[kUniformTriangles + 1u]; };
Triangle triangle_at(uint i) {
  if (kUniformTriangles > 0u) return uniform_triangles[i];
  return triangles[i];
}

// The scene's features (scene_types.h: kFeature*); every bit set is the general kernel.
layout(constant_id = 0) const uint kSceneFeatures = kFeatureAll;

#include "common/kernel/features.glsl"

#endif  // PT_GPU_KERNEL_BINDINGS_GLSL
