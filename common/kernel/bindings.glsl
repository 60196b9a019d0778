// The kernel's view of the scene: the flat arrays of scene_types.h and the per-pass
// parameters, as Vulkan buffers in GLSL and as plain globals in C++ (set by
// cpu_kernel_impl.h before each pass). The same names on both sides.
#ifndef PT_BINDINGS_GLSL
#define PT_BINDINGS_GLSL

#ifdef __cplusplus
inline const Triangle* triangles = nullptr;
inline const Sphere* spheres = nullptr;
inline const Material* materials = nullptr;
inline const PointLight* point_lights = nullptr;
inline FrameParams params;
inline uint* counters = nullptr;  // kCounterCount event counters, updated atomically
inline const Light* lights = nullptr;  // the light table (stage4)
inline thread_local uint rng_state = 0u;  // the random-number state of one invocation
// The triangles again as a structure of arrays for the CPU's block test (intersect_cpu.h,
// pt::TriangleSoa): nullptr means the plain loop over triangles[].
inline const float* triangle_soa = nullptr;
inline uint triangle_soa_stride = 0u;  // floats per array (the padded triangle count)
inline Triangle triangle_at(uint i) { return triangles[i]; }
#else
layout(std430, set = 0, binding = 0) readonly buffer TriangleBuffer { Triangle triangles[]; };
layout(std430, set = 0, binding = 1) readonly buffer SphereBuffer { Sphere spheres[]; };
layout(std430, set = 0, binding = 2) readonly buffer MaterialBuffer { Material materials[]; };
layout(std430, set = 0, binding = 3) readonly buffer PointLightBuffer { PointLight point_lights[]; };
layout(std140, set = 0, binding = 4) uniform ParamsBuffer { FrameParams params; };
layout(std430, set = 0, binding = 5) writeonly buffer OutputBuffer { vec4 pass_output[]; };
layout(std430, set = 0, binding = 6) buffer CounterBuffer { uint counters[]; };
layout(std430, set = 0, binding = 7) readonly buffer LightBuffer { Light lights[]; };
uint rng_state;  // the random-number state of one invocation
// The triangles again in a uniform buffer when the scene's fit in one (gpu_backend.cpp):
// lavapipe (Mesa 22's llvmpipe) reads a storage buffer lane by lane, a branch and a
// bounds test for every invocation and component, even at an index all invocations
// share, as the loop over the triangles has; from a uniform buffer such a read is one
// load for all. kUniformTriangles: how many the uniform copy can hold, 0 when it is not
// used (a specialization constant: the driver keeps only one of the two reads).
layout(constant_id = 1) const uint kUniformTriangles = 0u;
layout(std140, set = 0, binding = 8) uniform UniformTriangleBuffer { Triangle uniform_triangles[kUniformTriangles + 1u]; };
Triangle triangle_at(uint i) {
  if (kUniformTriangles > 0u) return uniform_triangles[i];
  return triangles[i];
}
#endif

#include "common/kernel/features.glsl"

#endif  // PT_BINDINGS_GLSL
