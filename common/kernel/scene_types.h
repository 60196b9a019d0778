// Data layouts shared by the host (C++) and the kernels (GLSL and C++): the scene as
// flat arrays (docs/README.md, "Scene and kernels"), one named field per value, laid out so
// that std430, std140 and C++ agree on offsets (see the note above struct Triangle).
// Article: the scene the intersection procedure of Eq. (2)-(5) searches, brute force.
#ifndef PT_SCENE_TYPES_H
#define PT_SCENE_TYPES_H

#ifdef __cplusplus
#include <glm/glm.hpp>
#include <cstddef>
#include <cstdint>
namespace pt {
using glm::vec2;
using glm::vec3;
using glm::vec4;
using uint = std::uint32_t;
#endif

// Material kinds (the contract (README.md), "Materials").
const uint kMaterialDiffuse = 0u;    // Lambertian, albedo = base colour
const uint kMaterialMirror = 1u;     // metallic 1, roughness 0: Schlick Fresnel, delta
const uint kMaterialConductor = 2u;  // metallic 1, roughness > 0: GGX, alpha = roughness^2
const uint kMaterialGlass = 3u;      // KHR_materials_transmission: smooth dielectric
const uint kMaterialMixed = 4u;      // 0 < metallic < 1: conductor w.p. metallic, else diffuse
// The glTF metallic-roughness material of a glTF file (the specification's Appendix B):
// with probability metallic the conductor (as kMaterialConductor / kMaterialMirror), else
// the dielectric: a GGX specular layer over a Lambert base, mixed by Fresnel
// (common/kernel/gltf_dielectric.glsl). Built-in scenes keep the kinds above.
const uint kMaterialDielectric = 5u;
// The two lobes of a dielectric whose layer is perfectly smooth (alpha < kGgxMirrorAlpha),
// which choose_lobe picks between: the layer's mirror reflection (a delta), and the base.
const uint kLobeSmoothLayer = 6u;
const uint kLobeSmoothBase = 7u;
// KHR_materials_transmission with roughness > 0: a rough dielectric (Walter et al. 2007,
// GGX reflection and refraction; common/kernel/rough_dielectric.glsl), alpha = roughness^2.
// Its Material.ior is relative: the index beyond the surface over the index on the side the
// ray arrives from (surface_material divides 1 by it on a back-face hit).
const uint kMaterialRoughGlass = 8u;
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

// Where the estimator's random numbers come from (FrameParams.sampler_kind, --sampler).
const uint kSamplerIndependent = 0u;  // independent uniform numbers (a PCG stream per sample)
const uint kSamplerSobol = 1u;        // Owen-scrambled Sobol points (common/kernel/sampler.glsl)

// How the triangles are searched (FrameParams.accel, --accel): every triangle (the
// article's brute force), or the bounding volume hierarchy (common/scene/bvh.h).
const uint kAccelNone = 0u;
const uint kAccelBvh = 1u;
// The deepest a BVH may be: the traversal's stack (common/kernel/bvh.glsl, gpu/bvh_walk.glsl)
// holds one node per level, and the build (common/scene/bvh.cpp) never goes deeper.
const uint kBvhStackSize = 64u;
// The GPU's stack (gpu/bvh_walk.glsl) holds a node as one number, its first_or_left above this many
// bits of its count (a leaf holds at most kBvhMaxLeaf = 4 triangles, common/scene/bvh.h),
// so first_or_left stays below 2^29 (build_bvh refuses more than 2^28 triangles).
const uint kBvhCountBits = 3u;

// Light kinds of the light table (stage4's light sampling).
const uint kLightTriangle = 0u;  // an emissive triangle: a point uniform on its area
const uint kLightSphere = 1u;    // an emissive sphere: a direction in the cone it subtends
const uint kLightPoint = 2u;     // a KHR_lights_punctual light (point, spot, directional): a delta

// Kinds of KHR_lights_punctual light (PointLight.kind).
const uint kPunctualPoint = 0u;        // from a point, equally in every direction
const uint kPunctualSpot = 1u;         // from a point, within a cone about `direction`
const uint kPunctualDirectional = 2u;  // from infinitely far, along `direction` (a sun)

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
const uint kFeatureTextures = 1u << 11u;        // textures or vertex colours (texture.glsl)
const uint kFeatureAlphaMask = 1u << 12u;       // alphaMode MASK: holes rays pass (intersect.glsl)
const uint kFeatureDielectric = 1u << 13u;      // glTF's dielectric: specular layer over a base
const uint kFeatureShadingNormals = 1u << 14u;  // vertex normals, normal maps (shading_normal.glsl)
const uint kFeatureRoughGlass = 1u << 15u;      // rough dielectric transmission (kMaterialRoughGlass)
const uint kFeatureEnvironment = 1u << 16u;     // the sky is an HDR image (environment.glsl); with kFeatureSky
const uint kFeatureAll = (1u << 17u) - 1u;

// Event counters the kernels keep (counters[] of cpu/kernel_bindings.h and gpu/kernel_bindings.glsl), reported by the summary.
const uint kCounterDepthCap = 0u;       // paths stopped by the depth cap (a safety net)
const uint kCounterZeroPdf = 1u;        // paths ended by a zero pdf or a non-finite weight
const uint kCounterNonFinite = 2u;      // samples dropped because they were NaN or Inf
const uint kCounterNonFinitePixel = 3u; // not a count: the lowest pixel index with a dropped sample (atomicMin)
const uint kCounterCount = 4u;
// The slot of render_pixel()'s vec4 (render_pixel.glsl) that holds the root of the sum of the
// samples' squared luminance; the others hold the sum of their radiance.
const uint kPassRootSumSquares = 3u;

// Every vec3 sits at a 16-byte offset and is followed by a 4-byte scalar, and every struct
// is a multiple of 16 bytes: then std430 (the storage buffers), std140 (the uniform blocks
// of FrameParams and of uniform_triangles) and C++ (glm::vec3: 12 bytes, alignment 4) give
// the same offsets, which the static_asserts below check on the C++ side.
struct Triangle {
  vec3 p0;        // vertex 0 (world space)
  uint material;  // index into materials[]
  vec3 p1;        // vertex 1
  uint light;     // index into lights[], or kNoLight
  vec3 p2;        // vertex 2; counter-clockwise seen from the front
  uint flags;     // kTriangle* bits
};

// Triangle.flags: its material has an alpha mask (alphaMode MASK), so a ray's hit on it is
// checked for a hole (intersect.glsl cut_out); other triangles are never looked up.
const uint kTriangleMasked = 1u;
// Triangle.flags: it is shaded with its own normals (vertex normals that differ from its face
// normal, or a normal map; common/kernel/shading_normal.glsl reads its TriangleShading); the
// others are shaded with the geometric normal, as before.
const uint kTriangleShadingNormals = 2u;

struct Sphere {
  vec3 center;    // centre (world space)
  float radius;
  uint material;  // index into materials[]
  uint light;     // index into lights[], or kNoLight
  uint pad0;      // unused
  uint pad1;      // unused
};

struct Material {
  vec3 base_color;     // albedo / F0 / glass tint
  float metallic;      // 0: diffuse, 1: conductor, between: mixed (kMaterialMixed)
  vec3 emission;       // emitted radiance (factor x strength)
  uint double_sided;   // 1: emits from both faces, 0: from the front face only
  float alpha;         // GGX alpha (roughness^2)
  float transmission;  // KHR_materials_transmission's factor
  float ior;           // index of refraction (glass)
  uint kind;           // kMaterial*
  vec3 specular_f0;    // kMaterialDielectric: the layer's Fresnel F0 per channel (ior,
                       // KHR_materials_specular's specularColorFactor; at most 1)
  float specular;      // kMaterialDielectric: the layer's weight (specularFactor, default 1)
};

// A KHR_lights_punctual light: a point light, a spot light or a directional light.
struct PointLight {
  vec3 position;    // world position (point, spot)
  uint kind;        // kPunctual*
  vec3 intensity;   // colour x intensity: W/sr (point, spot), irradiance W/m^2 (directional)
  float cos_outer;  // spot: cosine of the outer cone angle, where the light ends
  vec3 direction;   // spot, directional: the unit direction the light travels (node's -Z)
  float cos_inner;  // spot: cosine of the inner cone angle, within which it is full
};

// One entry of the light table: lights are picked in proportion to their power.
struct Light {
  uint kind;   // kLight*
  uint index;  // index into triangles[], spheres[] or point_lights[]
  float pick;  // probability of picking it
};

// One cell of the light table's alias table (lights.glsl pick_light_entry; Walker's alias method,
// built by Vose's algorithm in scene_lights.cpp). A number u in [0, 1) chooses cell
// k = uint(u x light_count), all of equal probability; within it, the fraction below
// `threshold` picks light k and the rest light `alias`. Each cell keeps a copy of both
// entries, so that picking a light reads this one record and not the table.
struct LightAlias {
  float threshold;  // the part of the cell that picks light k itself, in [0, 1]
  uint alias;       // the entry picked in the rest of the cell
  Light own;        // lights[k]
  Light other;      // lights[alias]
};

// Triangle lights whose triangles follow one another as the lights do: light first_light + i
// is triangle first_triangle + i, up to the next run. Only the CPU reads them, to ask the
// memory for a light's triangle before the light's cell has arrived
// (cpu/kernel_bindings.h prefetch_light_triangle).
struct LightRun {
  uint first_light;
  uint first_triangle;
};

struct Camera {
  vec3 origin;     // eye position
  uint kind;       // kCamera*
  vec3 forward;    // unit view direction (the node's -Z)
  float extent_x;  // perspective: tan(yfov/2) * aspect; orthographic: xmag (half-extent)
  vec3 right;      // unit image +x
  float extent_y;  // perspective: tan(yfov/2); orthographic: ymag (half-extent)
  vec3 up;         // unit image +y
  float clip_start;  // rays start on the plane this far along forward (Cycles' clip start,
                     // smallpt's 140); 0 for glTF cameras (znear is not read)
};

// Everything a pass needs besides the arrays: one uniform block on the GPU.
struct FrameParams {
  Camera camera;
  vec3 sky;                // radiance of rays that leave the scene
  float sky_pick;          // probability that light sampling picks the sky (the light
                           // table shares the rest)
  uint width;              // image size in pixels
  uint height;
  uint first_sample;       // sample index of this pass's first sample
  uint sample_count;       // samples per pixel in this pass
  uint triangle_count;     // entries of triangles[]
  uint sphere_count;       // entries of spheres[]
  uint material_count;     // entries of materials[]
  uint point_light_count;  // entries of point_lights[]
  uint seed;               // the random-number seed of the render
  uint roulette;           // kRoulette*
  uint depth_cap;          // bounces after which a path stops (a safety net)
  uint first_row;          // the first image row of this dispatch (GPU)
  uint light_count;        // entries of the light table lights[]
  float scene_radius;      // the radius of the scene's bounding sphere (ray offsets scale with it)
  uint accel;              // kAccel*: the BVH or every triangle (the same hits)
  uint sampler_kind;       // kSampler*: which numbers feed the estimator (sampler.glsl)
  // The environment map (kFeatureEnvironment, common/kernel/environment.glsl): its size in
  // texels (0 without one) and its turn about +Y (--env-rotate) as a cosine and a sine.
  uint env_width;
  uint env_height;
  float env_cos;
  float env_sin;
  // What a stage's own step before the render measured, for its kernel to read (the one
  // hook a stage may provide: StageKernels::before_render, common/render/backend.h); zero
  // for the stages without one. stage6_variance_aware keeps its MIS factors here.
  vec4 stage_params;
};

// One node of the bounding volume hierarchy over the triangles (common/scene/bvh.h), in a
// flat array with the root at 0. An inner node's children are nodes first_or_left and
// first_or_left + 1; a leaf's triangles are bvh_indices[first_or_left ... + count - 1].
struct BvhNode {
  vec3 lo;             // the box's lower corner (rounded outward)
  uint first_or_left;  // leaf: first entry of bvh_indices[]; inner node: the left child
  vec3 hi;             // the box's upper corner (rounded outward)
  uint count;          // leaf: its triangles (1 or more); 0: an inner node
};

#ifdef __cplusplus
static_assert(sizeof(Triangle) == 48);
static_assert(offsetof(Triangle, p1) == 16 && offsetof(Triangle, p2) == 32);
static_assert(sizeof(Sphere) == 32);
static_assert(offsetof(Sphere, radius) == 12 && offsetof(Sphere, material) == 16);
static_assert(sizeof(Material) == 64);
static_assert(offsetof(Material, emission) == 16 && offsetof(Material, alpha) == 32);
static_assert(offsetof(Material, specular_f0) == 48);
static_assert(sizeof(PointLight) == 48);
static_assert(offsetof(PointLight, intensity) == 16 && offsetof(PointLight, direction) == 32);
static_assert(sizeof(Light) == 12);
static_assert(sizeof(LightRun) == 8);
static_assert(sizeof(LightAlias) == 32 && offsetof(LightAlias, own) == 8 && offsetof(LightAlias, other) == 20);
static_assert(sizeof(Camera) == 64);
static_assert(offsetof(Camera, forward) == 16 && offsetof(Camera, right) == 32 && offsetof(Camera, up) == 48);
static_assert(sizeof(FrameParams) == 176 && offsetof(FrameParams, env_width) == 144);
static_assert(offsetof(FrameParams, stage_params) == 160);
static_assert(offsetof(FrameParams, sky) == 64 && offsetof(FrameParams, width) == 80);
static_assert(offsetof(FrameParams, triangle_count) == 96 && offsetof(FrameParams, seed) == 112);
static_assert(offsetof(FrameParams, light_count) == 128 && offsetof(FrameParams, scene_radius) == 132);
static_assert(offsetof(FrameParams, accel) == 136 && offsetof(FrameParams, sampler_kind) == 140);
static_assert(sizeof(BvhNode) == 32 && offsetof(BvhNode, hi) == 16 && offsetof(BvhNode, count) == 28);
}  // namespace pt
#endif

// The records of textures, vertex colours and shading normals.
#include "common/kernel/texture_types.h"

#endif  // PT_SCENE_TYPES_H
