# pt_embed_shader(NAME SOURCE): compiles a compute shader to SPIR-V with glslangValidator
# at build time and writes NAME_spirv.h, a uint32_t array NAME_spirv[] to embed in C++.
# Includes resolve from the repository root and the generated folder (kernel_definitions.glsl).
# Sets NAME_SPIRV_HEADER to the generated header's path.
function(pt_embed_shader NAME SOURCE)
  set(header ${CMAKE_CURRENT_BINARY_DIR}/${NAME}_spirv.h)
  file(GLOB_RECURSE deps CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/common/kernel/* ${PROJECT_SOURCE_DIR}/gpu/*.glsl
       ${PROJECT_SOURCE_DIR}/stage*/*.glsl ${PROJECT_SOURCE_DIR}/labs/*.glsl)
  add_custom_command(
    OUTPUT ${header}
    COMMAND ${GLSLANG_VALIDATOR} --quiet -V --target-env vulkan1.1 -I${PROJECT_SOURCE_DIR} -I${PT_KERNEL_GENERATED_DIR}
            --vn ${NAME}_spirv -o ${header} ${SOURCE}
    DEPENDS ${SOURCE} ${deps} ${PT_KERNEL_GENERATED_DIR}/kernel_definitions.glsl
    COMMENT "Compiling ${NAME} to SPIR-V"
    VERBATIM)
  set(${NAME}_SPIRV_HEADER ${header} PARENT_SCOPE)
endfunction()
