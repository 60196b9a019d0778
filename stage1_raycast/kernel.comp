// The Vulkan compute shader of stage1: the integrator, then the shared entry point.
// Compiled to SPIR-V at build time by glslangValidator and embedded in the program.
#version 460
#extension GL_GOOGLE_include_directive : require
#include "common/kernel/scene_types.h"
#include "stage1_raycast/integrator.glsl"
#include "gpu/kernel_main.glsl"
