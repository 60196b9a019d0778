// Data layouts of textures, vertex colours and shading normals, shared by the host (C++)
// and the kernels (GLSL and C++) as scene_types.h shares the rest of the scene (and
// includes this file): the texture table, each material's texture slots, and what a
// triangle carries besides its corners, laid out by the rule above scene_types.h's struct
// Triangle. Not in the article: glTF's textured materials.
#ifndef PT_TEXTURE_TYPES_H
#define PT_TEXTURE_TYPES_H

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

// Textures (common/kernel/texture.glsl, issue #19): what a sampler does at the edges and
// between texels (glTF's sampler wrapS / wrapT and magFilter), and "no texture".
const uint kNoTexture = 0xffffffffu;
const uint kWrapRepeat = 0u;          // glTF REPEAT (10497), the default
const uint kWrapClampToEdge = 1u;     // glTF CLAMP_TO_EDGE (33071)
const uint kWrapMirroredRepeat = 2u;  // glTF MIRRORED_REPEAT (33648)
const uint kFilterLinear = 0u;        // bilinear between the 4 nearest texels, the default
const uint kFilterNearest = 1u;       // glTF magFilter NEAREST (9728): the nearest texel

// One entry of the texture table: an image in texels[] (8-bit RGBA, R in the low byte,
// rows from the image's top, as glTF's uv (0, 0) is its top-left corner) and its sampler.
struct Texture {
  uint offset;     // the first texel in texels[]
  uint width;      // in texels
  uint height;
  uint wrap_s;     // kWrap* along u
  uint wrap_t;     // kWrap* along v
  uint mag_filter; // kFilter*; also used when minifying (there are no mipmaps)
  uint texel_min;  // each channel's smallest texel, packed like the texels (the host's
  uint texel_max;  // feature mask reads them: the material kinds a texture can reach)
};

// The texture slots of MaterialTextures, as bits of its tex_coord_sets: a set bit reads the
// slot's texture through TEXCOORD_1, a clear one through TEXCOORD_0 (texture_lookup.glsl
// slot_uv).
const uint kSlotBaseColor = 0u;
const uint kSlotEmissive = 1u;
const uint kSlotMetallicRoughness = 2u;
const uint kSlotSpecular = 3u;
const uint kSlotSpecularColor = 4u;
const uint kSlotNormal = 5u;
const uint kSlotTransmission = 6u;

// The textures of one material, parallel to materials[] (empty when the scene has no
// textures and no vertex colours). Each slot: a texture index (or kNoTexture) and its
// KHR_texture_transform as the two rows of a 2x3 matrix: s = dot(row_s, (u, v, 1)), of
// the texture coordinate set its bit of tex_coord_sets names.
struct MaterialTextures {
  vec3 base_color_s;           // base colour texture (sRGB), row s of its uv transform
  uint base_color;             // textures[] index, or kNoTexture
  vec3 base_color_t;           // row t
  float metallic_factor;       // pbrMetallicRoughness.metallicFactor
  vec3 emissive_s;             // emissive texture (sRGB)
  uint emissive;
  vec3 emissive_t;
  float roughness_factor;      // pbrMetallicRoughness.roughnessFactor
  vec3 metallic_roughness_s;   // metallic-roughness texture (linear: roughness G, metallic B)
  uint metallic_roughness;
  vec3 metallic_roughness_t;
  uint enabled;                // 1 in a scene's own entries; 0 in the neutral entries a
                               // backend binds for a scene without textures (nothing more is read)
  float base_alpha;            // baseColorFactor's alpha (alphaMode MASK)
  float alpha_cutoff;          // alphaMode MASK: alpha below this is a hole; 0: opaque
  uint tex_coord_sets;         // bit kSlot*: that slot reads TEXCOORD_1 (clear: TEXCOORD_0)
  uint pad1;                   // unused
  vec3 specular_s;             // KHR_materials_specular's specularTexture (linear: A scales
  uint specular;               // specularFactor, Material.specular)
  vec3 specular_t;
  float pad2;                  // unused
  vec3 specular_color_s;       // its specularColorTexture (sRGB: RGB scales specularColorFactor)
  uint specular_color;
  vec3 specular_color_t;
  float pad3;                  // unused
  vec3 specular_color_factor;  // specularColorFactor, which the texture scales before the
  float pad4;                  // layer's F0 is clamped to 1 (texture.glsl with_specular)
  vec3 normal_s;               // normal texture (linear; tangent space, glTF's normalTexture)
  uint normal;                 // textures[] index, or kNoTexture
  vec3 normal_t;
  float normal_scale;          // normalTexture.scale: scales the x and y of the map's normal
  vec3 transmission_s;         // KHR_materials_transmission's transmissionTexture (linear: R
  uint transmission;           // scales transmissionFactor, Material.transmission)
  vec3 transmission_t;
  float pad5;                  // unused
};

// What a triangle carries besides its corners, parallel to triangles[] (empty when the
// scene has no textures and no vertex colours): TEXCOORD_0, TEXCOORD_1 and COLOR_0 at its
// corners (uv (0, 0) and colour 1 where the primitive has none).
struct TriangleAttributes {
  vec2 uv0;      // TEXCOORD_0 at p0
  vec2 uv1;      // at p1
  vec2 uv2;      // at p2
  vec2 set1_uv0; // TEXCOORD_1 at p0
  vec4 color0;   // COLOR_0 at p0 (RGBA, linear)
  vec4 color1;
  vec4 color2;
  vec2 set1_uv1; // TEXCOORD_1 at p1
  vec2 set1_uv2; // at p2
};

// A triangle's shading frame at its corners, parallel to triangles[] (empty when no triangle
// is flagged kTriangleShadingNormals): glTF's NORMAL and TANGENT in world space (normals by
// the inverse transpose of the node's transform), tangents made from the UVs where the file
// has none. common/kernel/shading_normal.glsl interpolates them.
struct TriangleShading {
  vec3 normal0;        // unit vertex normal at p0
  float pad0;          // unused
  vec3 normal1;        // at p1
  float pad1;
  vec3 normal2;        // at p2
  float pad2;
  vec3 tangent0;       // unit tangent at p0 (the direction of increasing u)
  float handedness0;   // +1 or -1: the bitangent is handedness * cross(normal, tangent)
  vec3 tangent1;
  float handedness1;
  vec3 tangent2;
  float handedness2;
};

#ifdef __cplusplus
static_assert(sizeof(Texture) == 32);
static_assert(sizeof(MaterialTextures) == 256 && offsetof(MaterialTextures, emissive_s) == 32);
static_assert(offsetof(MaterialTextures, base_alpha) == 96 && offsetof(MaterialTextures, tex_coord_sets) == 104);
static_assert(offsetof(MaterialTextures, specular_s) == 112 && offsetof(MaterialTextures, specular_t) == 128);
static_assert(offsetof(MaterialTextures, specular_color_s) == 144 && offsetof(MaterialTextures, specular_color_t) == 160);
static_assert(offsetof(MaterialTextures, specular_color_factor) == 176);
static_assert(offsetof(MaterialTextures, normal_s) == 192 && offsetof(MaterialTextures, normal_scale) == 220);
static_assert(offsetof(MaterialTextures, transmission_s) == 224 && offsetof(MaterialTextures, transmission_t) == 240);
static_assert(sizeof(TriangleShading) == 96 && offsetof(TriangleShading, normal2) == 32);
static_assert(offsetof(TriangleShading, tangent0) == 48 && offsetof(TriangleShading, handedness2) == 92);
static_assert(offsetof(MaterialTextures, metallic_roughness_s) == 64 && offsetof(MaterialTextures, enabled) == 92);
static_assert(sizeof(TriangleAttributes) == 96 && offsetof(TriangleAttributes, uv2) == 16);
static_assert(offsetof(TriangleAttributes, set1_uv0) == 24 && offsetof(TriangleAttributes, color0) == 32);
static_assert(offsetof(TriangleAttributes, color2) == 64 && offsetof(TriangleAttributes, set1_uv1) == 80);
static_assert(offsetof(TriangleAttributes, set1_uv2) == 88);
}  // namespace pt
#endif

#endif  // PT_TEXTURE_TYPES_H
