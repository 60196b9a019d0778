// The functions the shared kernel code declares and the build defines, for a C++ kernel
// (included INSIDE its namespace, after the kernel code that uses them): the samplers the
// labs ask for (kernel_definitions.glsl, written by the build: the reference files of
// common/kernel, or a lab's file in that lab's build; cmake/Labs.cmake), and the CPU's
// searches over the triangles (triangle_lanes.h, through the BVH of bvh.glsl when there is
// one) and over the spheres (sphere_lanes.h).
#include "common/kernel/intersect.glsl"
#include "kernel_definitions.glsl"
#include "common/kernel/bvh.glsl"
#include "cpu/triangle_lanes.h"
#include "cpu/sphere_lanes.h"
