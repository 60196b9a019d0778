// Data layouts shared by the host (C++) and the kernels (GLSL and C++): the scene as
// flat arrays (docs/README.md, "Scene and kernels"). Every struct is made of 16-byte vectors
// so that std430 and C++ agree on offsets; the C++ side checks sizes with static_assert.
// Article: the scene the intersection procedure of Eq. (2)-(5) searches, brute force.
#ifndef PT_SCENE_TYPES_H
#define PT_SCENE_TYPES_H

#ifdef __cplusplus
#include <glm/glm.hpp>
#include <cstdint>
namespace pt {
using glm::vec4;
using glm::uvec4;
using uint = std::uint32_t;
#endif

// Material kinds (the contract (README.md), "Materials").
const uint kMaterialDiffuse = 0u;    // Lambertian, albedo = base colour
const uint kMaterialMirror = 1u;     // metallic 1, roughness 0: Schlick Fresnel, delta
const uint kMaterialConductor = 2u;  // metallic 1, roughness > 0: GGX, alpha = roughness^2
const uint kMaterialGlass = 3u;      // KHR_materials_transmission: smooth dielectric
const uint kMaterialMixed = 4u;      // 0 < metallic < 1: conductor w.p. metallic, else diffuse
// A GGX conductor smoother than this is a perfect mirror (a delta): below it the float
// evaluation of D(h) = alpha^2 / (pi (...)^2) at the peak under- and overflows (alpha 0:
// 0 / 0), and the lobe is narrower than a float direction can resolve anyway (docs/stability.md).
const float kGgxMirrorAlpha = 1e-7f;

// Primitive kinds, as the intersection search reports them.
const uint kPrimNone = 0u;
const uint kPrimTriangle = 1u;
const uint kPrimSphere = 2u;

// Camera kinds (glTF cameras, the contract (README.md) "Camera").
const uint kCameraPerspective = 0u;
const uint kCameraOrthographic = 1u;

// Russian roulette modes (stage2 onwards).
const uint kRouletteFixed = 0u;       // the article: continue with probability 1/2
const uint kRouletteThroughput = 1u;  // continue with the path weight's largest component

const uint kNoLight = 0xffffffffu;

// Light kinds of the light table (stage4's light sampling).
const uint kLightTriangle = 0u;  // an emissive triangle: a point uniform on its area
const uint kLightSphere = 1u;    // an emissive sphere: a direction in the cone it subtends
const uint kLightPoint = 2u;     // a KHR_lights_punctual point light: a delta

// Scene features (issue "model only what a scene requires"): the loader derives the set a
// scene uses (scene.h: scene_feature_mask), and each kernel is specialised to it
// (features.glsl): code for a feature the scene lacks is never run, nor compiled in.
const uint kFeatureTriangles = 1u << 0u;        // shapes
const uint kFeatureSpheres = 1u << 1u;
const uint kFeatureDiffuse = 1u << 2u;          // lobes a material may scatter by
const uint kFeatureMirror = 1u << 3u;
const uint kFeatureConductor = 1u << 4u;        // GGX
const uint kFeatureGlass = 1u << 5u;
const uint kFeatureMixed = 1u << 6u;            // a material that picks one of two lobes
const uint kFeatureTriangleLights = 1u << 7u;   // lights
const uint kFeatureSphereLights = 1u << 8u;
const uint kFeaturePointLights = 1u << 9u;
const uint kFeatureSky = 1u << 10u;
const uint kFeatureAll = (1u << 11u) - 1u;

// Event counters the kernels keep (counters[] of cpu/kernel_bindings.h and gpu/kernel_bindings.glsl), reported by the summary.
const uint kCounterDepthCap = 0u;       // paths stopped by the depth cap (a safety net)
const uint kCounterZeroPdf = 1u;        // paths ended by a zero pdf or a non-finite weight
const uint kCounterNonFinite = 2u;      // samples dropped because they were NaN or Inf
const uint kCounterNonFinitePixel = 3u; // the lowest pixel index with a dropped sample
const uint kCounterLoopLimit = 4u;      // pixel passes whose loops the driver cut short (lavapipe)
const uint kCounterCount = 5u;

struct Triangle {
  vec4 p0;     // xyz: vertex 0 (world space)
  vec4 p1;     // xyz: vertex 1
  vec4 p2;     // xyz: vertex 2; counter-clockwise seen from the front
  uvec4 info;  // x: material index, y: light index or kNoLight
};

struct Sphere {
  vec4 center_radius;  // xyz: centre, w: radius
  uvec4 info;          // x: material index, y: light index or kNoLight
};

struct Material {
  vec4 base_color;  // rgb: albedo / F0 / glass tint
  vec4 emission;    // rgb: emitted radiance (factor x strength), w: 1 if double-sided
  vec4 params;      // x: metallic, y: GGX alpha (roughness^2), z: transmission, w: ior
  uvec4 kind;       // x: kMaterial*
};

struct PointLight {
  vec4 position;   // xyz: world position
  vec4 intensity;  // rgb: radiant intensity, W/sr (colour x intensity)
};

// One entry of the light table: lights are picked in proportion to their power.
struct Light {
  uvec4 info;  // x: kLight*, y: index into triangles[], spheres[] or point_lights[]
  vec4 pick;   // x: probability of picking it, y: cumulative probability up to it
};

struct Camera {
  vec4 origin;   // xyz: eye position
  vec4 forward;  // xyz: unit view direction (the node's -Z)
  vec4 right;    // xyz: unit image +x
  vec4 up;       // xyz: unit image +y
  vec4 extent;   // perspective: x = tan(yfov/2) * aspect, y = tan(yfov/2);
                 // orthographic: x = xmag, y = ymag (half-extents)
  uvec4 kind;    // x: kCamera*
};

// Everything a pass needs besides the arrays: one uniform block on the GPU.
struct FrameParams {
  Camera camera;
  vec4 sky;        // rgb: radiance of rays that leave the scene; w: probability that
                   // light sampling picks the sky (the light table shares the rest)
  uvec4 image;     // x: width, y: height, z: first sample index of this pass, w: samples
  uvec4 counts;    // x: triangles, y: spheres, z: materials, w: point lights
  uvec4 options;   // x: seed, y: roulette mode, z: depth cap, w: first row of the dispatch
  uvec4 lights;    // x: entries of the light table, yzw: unused
  vec4 scale;      // x: the radius of the scene's bounding sphere (ray offsets scale with it)
};

#ifdef __cplusplus
static_assert(sizeof(Triangle) == 64);
static_assert(sizeof(Sphere) == 32);
static_assert(sizeof(Material) == 64);
static_assert(sizeof(PointLight) == 32);
static_assert(sizeof(Camera) == 96);
static_assert(sizeof(Light) == 32);
static_assert(sizeof(FrameParams) == 192);
}  // namespace pt
#endif

#endif  // PT_SCENE_TYPES_H
