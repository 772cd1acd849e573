# tp2_embed_shader(OUT VAR SOURCE DEFINES): compiles GLSL SOURCE to SPIR-V
# with glslangValidator and writes it as the C array VAR into
# ${CMAKE_BINARY_DIR}/OUT.h, rebuilt when the source or TP2_SHADER_DEPS
# (the headers it includes) change.
function(tp2_embed_shader out var source defines)
  set(header ${CMAKE_BINARY_DIR}/${out}.h)
  separate_arguments(define_list UNIX_COMMAND "${defines}")
  add_custom_command(
    OUTPUT ${header}
    COMMAND ${GLSLANG_VALIDATOR} -V --target-env vulkan1.1 --quiet
            -I${CMAKE_SOURCE_DIR}/shaders ${define_list}
            --vn ${var} -o ${header} ${CMAKE_SOURCE_DIR}/${source}
    DEPENDS ${CMAKE_SOURCE_DIR}/${source} ${TP2_SHADER_DEPS}
    COMMENT "Compiling ${source} ${defines} to SPIR-V"
    VERBATIM)
endfunction()
