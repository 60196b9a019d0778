# The labs (docs/labs/README.md): one per stage of the article (Eq. 2 to 5), each asking the
# student to write the stage's central function in labs/labN.glsl.
#   -DPT_LAB=N (1-4)       the student's build: lab N's functions are the student's versions
#                          (stubs that fail loudly until written), on both backends.
#   -DPT_LAB_CHECK=ON      the CI's check build: the stub of lab $PT_LAB_STUB is chosen at run
#                          time on the CPU, so one build shows every lab's tests failing
#                          (tools/expect_lab_failure.sh). Use with PT_CPU_GENERAL_ONLY and build only
#                          pt_tests.
#   -DPT_CPU_GENERAL_ONLY=ON  compile each stage's CPU kernel once (all features) instead of
#                          once per feature variant: a faster build (the sanitizer and
#                          lab-check builds use it); the images are the same.
set(PT_LAB 0 CACHE STRING "Lab mode: 1-4 builds lab N with the student's labs/labN.glsl; 0 is the normal build")
option(PT_LAB_CHECK "Check build: PT_LAB_STUB=N at run time selects lab N's stubs on the CPU" OFF)
option(PT_CPU_GENERAL_ONLY "Compile one general CPU kernel per stage instead of feature variants" OFF)
if(NOT PT_LAB MATCHES "^[0-4]$")
  message(FATAL_ERROR "PT_LAB is '${PT_LAB}': use -DPT_LAB=1, 2, 3 or 4 for a lab (docs/labs/README.md), or 0 for the normal build")
endif()
if(PT_LAB AND PT_LAB_CHECK)
  message(FATAL_ERROR "PT_LAB and PT_LAB_CHECK exclude each other: use PT_LAB=N for a student's build, PT_LAB_CHECK=ON for the CI check")
endif()
# The shaders depend on this file, so changing PT_LAB recompiles them (file(CONFIGURE)
# rewrites it only when the value changes).
set(PT_LAB_STAMP ${PROJECT_BINARY_DIR}/pt_lab_mode.txt)
file(CONFIGURE OUTPUT ${PT_LAB_STAMP} CONTENT "PT_LAB=${PT_LAB}\n")
if(PT_LAB)
  add_compile_definitions(PT_LAB=${PT_LAB})
  message(STATUS "Lab ${PT_LAB}: built with the student's labs/lab${PT_LAB}.glsl; grade with ctest -L lab${PT_LAB}")
endif()
if(PT_LAB_CHECK)
  add_compile_definitions(PT_LAB_CHECK)
endif()
