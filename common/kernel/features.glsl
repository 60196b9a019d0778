// The features this copy of a kernel is built for (scene_types.h: kFeature*), and the one
// test the shared code asks before running the code of a feature. On the GPU it is a
// specialization constant, set when the pipeline is made for a scene, so the driver's
// compiler removes the code of every feature the scene lacks; on the CPU it is a
// compile-time constant, one copy of the kernel per variant (cmake/PtStage.cmake). With
// every bit set (--all-features) the kernel is the general one of the article.
#ifndef PT_FEATURES_GLSL
#define PT_FEATURES_GLSL

#ifdef __cplusplus
#ifdef PT_CPU_FEATURES
const uint kSceneFeatures = PT_CPU_FEATURES;
#else
const uint kSceneFeatures = kFeatureAll;
#endif
#else
layout(constant_id = 0) const uint kSceneFeatures = kFeatureAll;
#endif

bool has_feature(uint feature) { return (kSceneFeatures & feature) != 0u; }

#endif  // PT_FEATURES_GLSL
