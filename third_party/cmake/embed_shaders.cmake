# Embeds shaders/*.glsl into a generated C++ file so the binaries run from any folder.
# trilab_embed_shaders(OUT file...) defines `trilab::shader_source(name)` lookups (render/shaders.h).
function(trilab_embed_shaders out)
    add_custom_command(
        OUTPUT ${out}
        COMMAND ${CMAKE_COMMAND} -DOUT=${out} "-DINPUTS=${ARGN}"
                -P ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/embed_shaders_script.cmake
        DEPENDS ${ARGN} ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/embed_shaders_script.cmake
        COMMENT "Embedding shaders"
        VERBATIM)
endfunction()
