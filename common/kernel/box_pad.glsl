// The slab test's margins (common/kernel/box_slab.glsl), apart from the test itself so that the
// CPU's SIMD walk (cpu/wide_bvh_walk.cpp), which tests boxes the same way on lanes, reads the
// same numbers without including lab 5's reference file (the grader hides that file from
// every build of a submission: tools/grade_lab.py). Part of the BVH, the step after the
// article's GPU section.
#ifndef PT_BOX_PAD_GLSL
#define PT_BOX_PAD_GLSL

// The box grows by this fraction of its corners' distance from the ray origin (summed over
// the axes) before the slab test: the watertight triangle test decides with errors of a
// few kGamma5 of that distance (intersect.glsl), so a triangle it hits lies inside the
// grown box, whatever the float rounding of either test (2^-15, about 100 kGamma5).
const float kBoxPad = 3.0517578e-05f;
// pbrt's 1 + 2 gamma(3): the far distance of a slab, rounded up past its own rounding.
const float kBoxRoundUp = 1.00000036f;

#endif  // PT_BOX_PAD_GLSL
