// What a lab's file may use besides the kernel (docs/labs/README.md): PT_LAB_NOT_WRITTEN,
// the value of a function the student has not written yet. It is NaN, which fails every
// test, and on the CPU it also says once on stderr which function is missing
// (labs/lab_hooks.h). The lab builds (cmake/Labs.cmake) compile labs/labN.glsl in place of
// the reference definitions of the functions lab N asks for.
#ifndef PT_LAB_SUPPORT_GLSL
#define PT_LAB_SUPPORT_GLSL

#ifdef __cplusplus
#define PT_LAB_NOT_WRITTEN(n, function) pt::lab::not_written(n, #function)
#else
#define PT_LAB_NOT_WRITTEN(n, function) uintBitsToFloat(0x7fc00000u)
#endif

#endif  // PT_LAB_SUPPORT_GLSL
