// Lab hooks (docs/labs/README.md): the few real functions a lab asks the student to write
// start with PT_LAB_HOOK(N, call), which returns the student's version from labs/labN.glsl
// instead when lab N is selected (PT_LAB=N at compile time; PT_LAB_STUB=N at run time in
// the C++ check build). In the normal build the hook is `if (0 == N)`, removed by the
// compiler, and the real function runs. The labs follow the article's Eq. 2 to 5.
#ifndef PT_LAB_GLSL
#define PT_LAB_GLSL

#ifndef PT_LAB
#define PT_LAB 0
#endif

#ifdef __cplusplus
#define PT_LAB_HOOK(n, call) if (pt::lab::selected() == (n)) return call
// A stub's value: NaN, said once on stderr.
#define PT_LAB_NOT_WRITTEN(n, function) pt::lab::not_written(n, #function)
#else
#define PT_LAB_HOOK(n, call) if (PT_LAB == (n)) return call
#define PT_LAB_NOT_WRITTEN(n, function) uintBitsToFloat(0x7fc00000u)
#endif

#endif  // PT_LAB_GLSL
