// The one test the shared kernel code asks before running the code of a scene feature
// (scene_types.h: kFeature*). kSceneFeatures, the set this copy of a kernel is built for,
// comes from the backend: a specialization constant on the GPU (gpu/kernel_bindings.glsl),
// a compile-time constant per CPU variant (cpu/kernel_bindings.h). With every bit set
// (--all-features) the kernel is the general one of the article.
#ifndef PT_FEATURES_GLSL
#define PT_FEATURES_GLSL

bool has_feature(uint feature) { return (kSceneFeatures & feature) != 0u; }

#endif  // PT_FEATURES_GLSL
