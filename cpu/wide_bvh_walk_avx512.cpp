// The wide BVH's walk (wide_bvh_walk.cpp; the step after the article's GPU section) compiled
// for AVX-512 on 8 lanes (its 32 vector registers). Not part of the article: machinery for
// the CPU's instruction sets, dispatched at run time.
#define PT_WIDE_WALK_ISA 2
#include "cpu/wide_bvh_walk.cpp"
