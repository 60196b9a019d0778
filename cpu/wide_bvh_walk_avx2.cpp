// The wide BVH's walk (wide_bvh_walk.cpp; the step after the article's GPU section) compiled
// for AVX2 on 8 lanes: its own copy, so that the hit mask becomes bits by vmovmskps. Not
// part of the article: machinery for the CPU's instruction sets, dispatched at run time.
#define PT_WIDE_WALK_ISA 1
#include "cpu/wide_bvh_walk.cpp"
