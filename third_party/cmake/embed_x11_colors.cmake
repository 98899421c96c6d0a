# Embeds the X11 colour names of Debian's x11-common (/usr/share/X11/rgb.txt) into a generated
# C++ table, so that the XPM reader knows every name X11 knows without retyping the table.
# trilab_embed_x11_colors(OUT) defines trilab::kX11Colors / kX11ColorCount (core/io/x11_colors.h).
find_file(TRILAB_X11_RGB_TXT rgb.txt PATHS /usr/share/X11 /usr/X11R6/lib/X11 /etc/X11
          NO_DEFAULT_PATH)
if(NOT TRILAB_X11_RGB_TXT)
    message(FATAL_ERROR "The X11 colour table rgb.txt was not found (Debian: apt-get install "
                        "x11-common, which installs /usr/share/X11/rgb.txt)")
endif()

function(trilab_embed_x11_colors out)
    add_custom_command(
        OUTPUT ${out}
        COMMAND ${CMAKE_COMMAND} -DIN=${TRILAB_X11_RGB_TXT} -DOUT=${out}
                -P ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/embed_x11_colors_script.cmake
        DEPENDS ${TRILAB_X11_RGB_TXT}
                ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/embed_x11_colors_script.cmake
        COMMENT "Embedding the X11 colour names from ${TRILAB_X11_RGB_TXT}"
        VERBATIM)
endfunction()
