# pt_add_stage(DIR): one stage of the article. Builds DIR/kernel.comp into embedded SPIR-V,
# the kernel library pt_DIR (the integrator compiled as C++ for the CPU, plus the SPIR-V),
# used by the program and the tests, and the program DIR itself from DIR/main.cpp.
function(pt_add_stage DIR)
  pt_embed_shader(${DIR} ${CMAKE_CURRENT_SOURCE_DIR}/kernel.comp)
  add_library(pt_${DIR} STATIC cpu_kernel.cpp ${${DIR}_SPIRV_HEADER})
  target_include_directories(pt_${DIR} PUBLIC ${CMAKE_CURRENT_BINARY_DIR})
  target_link_libraries(pt_${DIR} PUBLIC pt_common)
  add_executable(${DIR} main.cpp)
  target_link_libraries(${DIR} PRIVATE pt_${DIR} pt_gpu)
endfunction()
