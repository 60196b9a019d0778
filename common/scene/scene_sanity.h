// Whole-scene checks of a loaded glTF scene (scene_sanity.cpp): scenes that the float kernels
// would render as a black or infinite image without a word are refused (exit 3) or warned
// about, and the host memory its triangles will take is checked before the loader makes them.
// Not part of the article: machinery around its scenes (docs/README.md, "glTF loader").
#pragma once

#include <cstdint>
#include <string>

#include "common/scene/scene.h"

namespace pt {

// The largest emitted radiance (each component of emissiveFactor x emissiveStrength) a
// material may have. A sample is summed in 32-bit floats before the film adds it in double:
// radiance up to 1e18 leaves a factor of FLT_MAX / 1e18 = 3.4e20 (2^68) for what the kernels
// multiply it by on the way: 16 samples a pass sums per pixel (2^4), the peak of the sharpest
// GGX lobe that a light sample weighs radiance by before its solid angle shrinks it
// (1 / (pi alpha^2) = 3.2e13 at alpha = 1e-7, kGgxMirrorAlpha: 2^45), and stage2's worst
// throughput growth of 4 a bounce (2 cos / pdf with the roulette's 1/2) for about 9 bounces.
// docs/stability.md renders radiance 1e20 in the furnace, which has no such lobe.
inline constexpr double kMaxEmission = 1e18;

// The largest extent (longest side of the bounding box) of a scene's geometry. Every stage
// but stage1 takes a hit's normal as normalize(cross(p1 - p0, p2 - p0)) in float
// (intersect.glsl), whose squared length is an edge to the 4th power: it overflows
// (FLT_MAX = 3.4e38) for edges above 4.3e9. Measured: the Cornell box scaled to 4e9 across
// renders its image on stage4, to 1e10 across (5e9 x) it is 86% black and beyond all black.
inline constexpr double kMaxSceneExtent = 1e9;

// The smallest extent: the same 4th power must stay a normal float (FLT_MIN = 1.2e-38; GPUs
// flush smaller ones to zero, and the normal becomes NaN): (1e-8)^4 = 1e-32 leaves triangles
// down to 1/300 of the scene's size. Measured: the Cornell box 6e-11 across renders on the CPU
// (which keeps denormals), 2e-11 across is black.
inline constexpr double kMinSceneExtent = 1e-8;

// The largest |coordinate| of a scene's geometry and cameras: the watertight triangle test
// (intersect.glsl) forms products of three coordinates relative to the ray origin (t_scaled,
// its error bound delta_t), up to (2 x 1e12)^3 = 8e36, below FLT_MAX.
inline constexpr double kMaxSceneCoordinate = 1e12;

// Below this extent relative to its largest |coordinate| a scene is warned about: its
// coordinates are then known to about 2^-24 / 2^-12 = 1/4096 of its size and less, and its
// shapes snap visibly to the float grid.
inline constexpr double kMinRelativeExtent = 1.0 / 4096.0;

// Host bytes one triangle of a loaded scene takes at the peak of loading and BVH building:
// the Triangle (48), the BVH's nodes and leaf indices (about 24), the build's references
// (40: box, centroid, index), the CPU backend's triangle copy (36) and wide BVH (36 + nodes),
// rounded up to 192. Measured: peak RSS grows by 175-180 B per triangle (stage1, CPU backend,
// 1-4 million triangles). Triangles with texture coordinates or vertex colours add their
// TriangleAttributes (96); triangles with vertex normals or a normal map their TriangleShading (96).
inline constexpr std::uint64_t kSceneBytesPerTriangle = 192;
inline constexpr std::uint64_t kAttributeBytesPerTriangle = sizeof(TriangleAttributes);

// The host memory the loader may fill with triangles: the programs set it to
// pt::available_memory_bytes() (common/render/memory.h) before loading; 0 (the default)
// checks nothing.
void set_scene_memory_budget(std::uint64_t bytes);

// Refuses (exit 3, naming both numbers) `triangles` triangles whose bytes (above) exceed the
// budget, or more than the BVH takes (kBvhMaxTriangles), before the loader makes them; the
// sums that give `triangles` must not have overflowed (overflowed: refused as too many).
void check_triangle_budget(std::uint64_t triangles, bool overflowed, bool attributes, const std::string& file,
                           bool shading = false);

// After a glTF file is loaded: a camera whose transform is degenerate (scale 0, not finite,
// view and up axes parallel), geometry whose extent lies outside [kMinSceneExtent,
// kMaxSceneExtent] and coordinates beyond kMaxSceneCoordinate are refused (exit 3); an extent
// below kMinRelativeExtent of the coordinates is warned about.
void check_scene_sanity(const Scene& scene, const std::string& file);

}  // namespace pt
