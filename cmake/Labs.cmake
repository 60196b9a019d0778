# The labs (docs/labs/README.md): one per stage of the article (Eq. 2 to 5), lab 5 on the
# BVH that follows it (docs/acceleration.md), and lab 6 on stage5_mis's multiple importance
# sampling (docs/stage5_mis.md), each asking the student to write a few kernel
# functions in labs/labN.glsl. The kernel declares those
# functions and the build decides where their definitions come from: it writes
# kernel_definitions.glsl, which every kernel includes (cpu/kernel_support.h, the GPU
# kernels of cmake/PtStage.cmake), and picks stage1's integrator for lab 1.
#   (default)              the reference definitions in common/kernel/.
#   -DPT_LAB=N (1-6)       the student's build: lab N's functions come from labs/labN.glsl
#                          (stubs that fail loudly until written), on both backends.
#   -DPT_LAB_CHECK=ON      the CI's check build: on the CPU, PT_LAB_STUB=N at run time picks
#                          lab N's stubs (labs/check_definitions.h, labs/check_lab1.h), so one
#                          build shows every lab's tests failing (tools/expect_lab_failure.sh).
#                          Use with PT_CPU_GENERAL_ONLY and build only the tests.
#   -DPT_LAB_GRADING=ON    with PT_LAB=N, the grader's build (tools/grade_lab.py): on the CPU
#                          the student's functions are kept out of line (a GCC optimize
#                          pragma that inlining cannot cross), so that a test that loops in one
#                          of them stops in a frame that names it (tools/grading/stuck.py).
#   -DPT_LAB_GRADED_STAGES=stage2;stage4  with PT_LAB_GRADING, the stages whose CPU kernels
#                          lab N's tests run (the grader lists their tags): the other stages'
#                          kernels get labs/ungraded.h's traps instead of the student's code,
#                          so that each submission recompiles only the kernels its tests run.
#   -DPT_CPU_GENERAL_ONLY=ON  compile each stage's CPU kernel once instead of once per feature
#                          variant: a faster build (the sanitizer and lab-check builds use
#                          it); the images are the same.
#   -DPT_CPU_RUNTIME_FEATURES=ON  the CI's check build, with PT_CPU_GENERAL_ONLY: the CPU copy
#                          reads the render's feature set at run time, as the GPU's
#                          specialization constant gives it (cpu/kernel_bindings.h), so that
#                          its tests check every feature gate at the GPU's mask. It costs
#                          about 5% more compile per kernel, so a lab's build leaves it off.
set(PT_LAB_GRADED_STAGES "" CACHE STRING
    "Grading (PT_LAB_GRADING): the stages (stage1 ... stage6, or none) whose CPU kernels run lab PT_LAB's tests; the others get traps. Empty: every stage")
set(PT_LAB 0 CACHE STRING "Lab mode: 1-6 builds lab N with the student's labs/labN.glsl; 0 is the normal build")
option(PT_LAB_CHECK "Check build: PT_LAB_STUB=N at run time selects lab N's stubs on the CPU" OFF)
option(PT_LAB_GRADING "The grader's lab build: the student's functions out of line on the CPU" OFF)
option(PT_CPU_GENERAL_ONLY "Compile one general CPU kernel per stage instead of feature variants" OFF)
option(PT_CPU_RUNTIME_FEATURES "The CPU kernels read the render's feature set at run time (the check build)" OFF)
if(NOT PT_LAB MATCHES "^[0-6]$")
  message(FATAL_ERROR "PT_LAB is '${PT_LAB}': use -DPT_LAB=1, 2, 3, 4, 5 or 6 for a lab (docs/labs/README.md), or 0 for the normal build")
endif()
if(PT_LAB AND PT_LAB_CHECK)
  message(FATAL_ERROR "PT_LAB and PT_LAB_CHECK exclude each other: use PT_LAB=N for a student's build, PT_LAB_CHECK=ON for the CI check")
endif()

# The grader's #include of labs/labN.glsl (PT_LAB_GRADING), in out_var: GCC does not inline a
# function whose optimize options differ from its caller's, so the student's functions keep
# frames of their own, which name the one an endless loop is in (tools/grading/stuck.py). The
# handout's #includes come first, outside the pragma: the kernel's own functions in them stay
# inlined (read without a configure dependency: the file is the student's).
function(pt_lab_out_of_line lab out_var)
  file(STRINGS ${PROJECT_SOURCE_DIR}/labs/lab${lab}.glsl includes REGEX "^#include \"(common|labs)/[a-z_0-9/]+\\.glsl\"$")
  list(JOIN includes "\n" includes)
  string(CONCAT text "${includes}\n#ifdef __cplusplus\n#pragma GCC push_options\n#pragma GCC optimize(\"no-ipa-cp\")\n#endif\n"
                "#include \"labs/lab${lab}.glsl\"\n#ifdef __cplusplus\n#pragma GCC pop_options\n#endif\n")
  set(${out_var} "${text}" PARENT_SCOPE)
endfunction()

# Which file defines the functions each lab asks for: the reference, or the student's.
set(PT_KERNEL_GENERATED_DIR ${PROJECT_BINARY_DIR}/generated)
set(definitions "")
# A lab may ask for the functions of several files (lab 2: the uniform estimator and the
# roulette; lab 4: the triangle light and the emission rule); its own file replaces them all.
foreach(pair 2:common/kernel/uniform_hemisphere.glsl 2:common/kernel/russian_roulette.glsl
             3:common/kernel/cosine_hemisphere.glsl 4:common/kernel/triangle_light.glsl
             4:common/kernel/emission_rule.glsl 5:common/kernel/box_slab.glsl 6:common/kernel/mis.glsl)
  string(REGEX REPLACE ":.*" "" lab ${pair})
  string(REGEX REPLACE ".*:" "" reference ${pair})
  if(PT_LAB EQUAL lab)
    if(NOT definitions MATCHES "labs/lab${lab}.glsl")
      if(PT_LAB_GRADING)
        # A stage's CPU kernel that none of the lab's tests runs (PT_LAB_UNGRADED_KERNEL,
        # cmake/PtStage.cmake) gets the traps of labs/ungraded.h instead, so that it does not
        # include the student's file and a submission does not rebuild it.
        pt_lab_out_of_line(${lab} include)
        string(APPEND definitions "#if defined(__cplusplus) && defined(PT_LAB_UNGRADED_KERNEL)\n"
                                  "#include \"labs/ungraded.h\"\n#else\n${include}#endif\n")
      else()
        string(APPEND definitions "#include \"labs/lab${lab}.glsl\"\n")
      endif()
    endif()
  else()
    string(APPEND definitions "#include \"${reference}\"\n")
  endif()
endforeach()
if(PT_LAB_CHECK)
  set(definitions "#ifdef __cplusplus\n#include \"labs/check_definitions.h\"\n#else\n${definitions}#endif\n")
endif()
# file(CONFIGURE) rewrites it only when it changes, so the kernels recompile only then.
file(CONFIGURE OUTPUT ${PT_KERNEL_GENERATED_DIR}/kernel_definitions.glsl CONTENT
"// Written by cmake/Labs.cmake (PT_LAB=${PT_LAB}, PT_LAB_CHECK=${PT_LAB_CHECK}): the definitions of the
// kernel functions the labs ask for.
#ifndef PT_KERNEL_DEFINITIONS_GLSL
#define PT_KERNEL_DEFINITIONS_GLSL
${definitions}#endif
")
# The lab builds' compile options: the stubs' loud failure on the CPU (labs/lab_support.glsl)
# calls into labs/lab_hooks.h. Only the kernels include the labs' code, so only the targets
# made after this call (the stages, the tests, the bench) get them: the root CMakeLists.txt
# calls it after the libraries common/, cpu/ and gpu/ and the film's tools, which are then
# compiled with the same command lines as the Release build's, and a compiler cache that
# holds that build's objects serves a lab's set-up too (tools/grade_lab.py --compiler-cache).
function(pt_lab_compile_options)
  if(PT_LAB OR PT_LAB_CHECK)
    add_compile_options(-include ${PROJECT_SOURCE_DIR}/labs/lab_hooks.h)
    add_compile_definitions(PT_LAB=${PT_LAB})
  endif()
  if(PT_LAB_CHECK)
    add_compile_definitions(PT_LAB_CHECK)
  endif()
endfunction()
if(PT_LAB)
  message(STATUS "Lab ${PT_LAB}: built with the student's labs/lab${PT_LAB}.glsl; grade with ctest -L lab${PT_LAB}")
endif()
