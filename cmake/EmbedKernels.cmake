# Embeds the OpenCL sources (kernels/*.cl and the shared headers they include) into the
# binary, so `tessera` runs from any directory. Each file becomes an entry of a table
# keyed by its path relative to kernels/ (see host/opencl/kernel_source.h).
function(tessera_embed_kernels output)
  add_custom_command(
    OUTPUT ${output}
    COMMAND ${CMAKE_COMMAND} -DOUTPUT=${output} -DKERNEL_ROOT=${CMAKE_SOURCE_DIR}/kernels
            -P ${CMAKE_SOURCE_DIR}/cmake/EmbedKernelsScript.cmake
    DEPENDS ${ARGN} ${CMAKE_SOURCE_DIR}/cmake/EmbedKernelsScript.cmake
    COMMENT "Embedding OpenCL kernel sources")
endfunction()
