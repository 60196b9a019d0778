# pt_add_stage(DIR [CPU_GROUPS N] [USES_LIGHT_TABLE] [LAB N] [BEFORE_RENDER FN HEADER H SOURCES FILES...]):
# one stage of the article,
# made from its folder's integrator.glsl and main.cpp. The build writes the rest:
#   - DIR's GPU kernel: the backend's bindings, the integrator, the pixel loop and the GPU
#     entry point, compiled to SPIR-V and embedded (specialised per scene at run time);
#   - DIR's CPU kernel: the same integrator compiled as C++ inside namespace stageK::vI
#     (its functions of internal linkage, so that GCC inlines as a GPU compiler does; only
#     stageK::vI::cpu_kernel() is seen outside), once per CPU feature variant (the first N
#     coarse feature groups of cpu/cpu_variants.h switched on and off: 2^N copies);
#   - DIR/kernels.h: `stageK::kernels()`, the kernel in both forms (pt::StageKernels);
#   - the kernel library pt_DIR (used by the program and the tests) and the program DIR.
# USES_LIGHT_TABLE: the kernel reads the light table and the point lights (light sampling),
# so they are uploaded. BEFORE_RENDER FN: the stage's own step before the render, the C++
# function FN (a pt::BeforeRender, common/render/backend.h) declared in the stage's header
# DIR/H and defined in its SOURCES (host files of the stage's folder, built into
# pt_DIR): stage6's pilot. LAB N: lab N asks the student for this stage's integrator
# (cmake/Labs.cmake): its build compiles labs/labN.glsl in its place.
# Tests make kernels that are not stages the same way: INTEGRATOR FILE (instead of
# DIR/integrator.glsl), NAMESPACE NS (instead of DIR's stageK) and NO_PROGRAM.
function(pt_add_stage DIR)
  cmake_parse_arguments(ARG "USES_LIGHT_TABLE;NO_PROGRAM" "CPU_GROUPS;LAB;INTEGRATOR;NAMESPACE;BEFORE_RENDER;HEADER" "SOURCES" ${ARGN})
  if(NOT DEFINED ARG_CPU_GROUPS OR PT_CPU_GENERAL_ONLY)
    set(ARG_CPU_GROUPS 0)
  endif()
  string(REGEX MATCH "^stage[0-9]+" ns ${DIR})  # the stage's C++ namespace, e.g. stage4
  if(DEFINED ARG_NAMESPACE)
    set(ns ${ARG_NAMESPACE})
  endif()
  set(src ${PROJECT_SOURCE_DIR}/${DIR})
  set(out ${CMAKE_CURRENT_BINARY_DIR}/${DIR})
  set(integrator "${DIR}/integrator.glsl")
  if(DEFINED ARG_INTEGRATOR)
    set(integrator "${ARG_INTEGRATOR}")
  endif()
  set(cpu_include "#include \"${integrator}\"\n")
  if(DEFINED ARG_LAB AND PT_LAB EQUAL ARG_LAB)
    set(integrator "labs/lab${ARG_LAB}.glsl")
    set(cpu_include "#include \"${integrator}\"\n")
    if(PT_LAB_GRADING)  # the student's integrator out of line, as the other labs' functions
      pt_lab_out_of_line(${ARG_LAB} cpu_include)
    endif()
  elseif(DEFINED ARG_LAB AND PT_LAB_CHECK)
    set(cpu_include "#include \"labs/check_lab${ARG_LAB}.h\"\n")
  endif()

  file(CONFIGURE OUTPUT ${out}/kernel.comp CONTENT
"// Written by cmake/PtStage.cmake: ${DIR}'s Vulkan compute shader.
#version 460
#extension GL_GOOGLE_include_directive : require
#include \"common/kernel/scene_types.h\"
#include \"gpu/kernel_bindings.glsl\"
#include \"${integrator}\"
#include \"kernel_definitions.glsl\"
#include \"gpu/triangle_search.glsl\"
#include \"common/kernel/render_pixel.glsl\"
#include \"gpu/kernel_main.glsl\"
")
  pt_embed_shader(${DIR}_kernel ${out}/kernel.comp)
  add_custom_target(${DIR}_spirv DEPENDS ${${DIR}_kernel_SPIRV_HEADER})  # the GPU kernel alone

  math(EXPR count "1 << ${ARG_CPU_GROUPS}")
  # PT_CPU_RUNTIME_FEATURES (the check build's): the copy reads the render's feature set at
  # run time, as a GPU kernel's specialization constant gives it (cpu/kernel_bindings.h).
  set(kernel_defines "")
  if(PT_CPU_RUNTIME_FEATURES)
    set(kernel_defines "#define PT_CPU_RUNTIME_FEATURES\n")
  endif()
  # The grader's build (cmake/Labs.cmake, PT_LAB_GRADED_STAGES): a stage's kernel that none
  # of the lab's tests runs gets the traps of labs/ungraded.h in place of the student's code.
  if(PT_LAB_GRADING AND PT_LAB_GRADED_STAGES AND NOT ARG_NO_PROGRAM AND NOT ns IN_LIST PT_LAB_GRADED_STAGES)
    string(APPEND kernel_defines "#define PT_LAB_UNGRADED_KERNEL \"${ns}\"\n")
  endif()
  math(EXPR last "${count} - 1")
  set(sources)
  set(declarations)
  set(table)
  foreach(i RANGE ${last})
    file(CONFIGURE OUTPUT ${out}/cpu_kernel_v${i}.cpp CONTENT
"// Written by cmake/PtStage.cmake: CPU variant ${i} of ${count} of ${DIR}'s kernel.
#define PT_CPU_VARIANT ${i}
#define PT_CPU_VARIANT_COUNT ${count}
${kernel_defines}#include \"cpu/cpu_variants.h\"
#include \"cpu/kernel_prelude.h\"
#include \"cpu/kernel_scene.h\"

// The kernel's functions have internal linkage (the unnamed namespace), so that GCC may inline
// those called once (camera_ray, surface_at, ...) into the pixel loop, as a GPU compiler does:
// with external linkage it kept each a call, its structures passed through memory (issue 50,
// round nine). Those this stage does not call go unused, hence the pragma.
#pragma GCC diagnostic ignored \"-Wunused-function\"
namespace ${ns}::v${i} {
namespace kernel {
namespace {
#include \"cpu/kernel_begin.h\"
${cpu_include}#include \"cpu/kernel_end.h\"
}  // namespace
}  // namespace kernel
pt::CpuKernel cpu_kernel() { return kernel::cpu_kernel(); }
}  // namespace ${ns}::v${i}
")
    list(APPEND sources ${out}/cpu_kernel_v${i}.cpp)
    string(APPEND declarations "namespace v${i} { pt::CpuKernel cpu_kernel(); }\n")
    string(APPEND table "v${i}::cpu_kernel(), ")
  endforeach()
  if(ARG_USES_LIGHT_TABLE)
    set(uses_lights true)
  else()
    set(uses_lights false)
  endif()
  set(before_render nullptr)
  set(before_render_include "")
  if(DEFINED ARG_BEFORE_RENDER)
    set(before_render "&${ARG_BEFORE_RENDER}")
    set(before_render_include "#include \"${DIR}/${ARG_HEADER}\"\n")
  endif()
  list(TRANSFORM ARG_SOURCES PREPEND ${src}/)
  file(CONFIGURE OUTPUT ${out}/kernels.h CONTENT
"// Written by cmake/PtStage.cmake: ${DIR}'s kernel in both forms (C++ for the CPU, SPIR-V for Vulkan).
#pragma once

#include \"common/render/backend.h\"

namespace ${ns} {
pt::StageKernels kernels();
}
")
  file(CONFIGURE OUTPUT ${out}/kernels.cpp CONTENT
"// Written by cmake/PtStage.cmake: ${DIR}'s kernel in both forms, its CPU variants in the
// order of cpu/cpu_variants.h.
#include \"${DIR}/kernels.h\"
#include \"cpu/kernel_scene.h\"
${before_render_include}
namespace ${ns} {
${declarations}
std::span<const std::uint32_t> spirv();  // spirv.cpp
pt::StageKernels kernels() {
  static const pt::CpuKernel cpu[] = {${table}};
  return pt::StageKernels{\"${DIR}\", cpu, spirv(), ${uses_lights}, ${before_render}};
}
}  // namespace ${ns}
")
  # The SPIR-V in a file of its own: a change to the GPU kernel (a lab's file, in the
  # grader's build of every submission) recompiles this array alone, not kernels.cpp and
  # the headers it needs (issue #47: 0.5 CPU s instead of 1.2 per stage).
  file(CONFIGURE OUTPUT ${out}/spirv.cpp CONTENT
"// Written by cmake/PtStage.cmake: ${DIR}'s kernel compiled to SPIR-V (${DIR}_kernel_spirv.h).
#include <cstdint>
#include <span>
#include \"${DIR}_kernel_spirv.h\"

namespace ${ns} {
std::span<const std::uint32_t> spirv() { return ${DIR}_kernel_spirv; }
}  // namespace ${ns}
")
  add_library(pt_${DIR} STATIC ${sources} ${ARG_SOURCES} ${out}/kernels.cpp ${out}/spirv.cpp ${${DIR}_kernel_SPIRV_HEADER})
  target_include_directories(pt_${DIR} PUBLIC ${CMAKE_CURRENT_BINARY_DIR} PRIVATE ${out})
  target_link_libraries(pt_${DIR} PUBLIC pt_common)
  if(NOT ARG_NO_PROGRAM)
    add_executable(${DIR} ${src}/main.cpp)
    target_link_libraries(${DIR} PRIVATE pt_${DIR} pt_cpu pt_gpu)
  endif()
endfunction()
