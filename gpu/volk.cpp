// The volk meta-loader's implementation: Vulkan is opened at run time (libvulkan.so.1),
// so the programs start and the CPU backend works on machines without Vulkan.
#define VOLK_IMPLEMENTATION
#include <volk.h>
