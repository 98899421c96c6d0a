# The viewer's layout rule, checked on the rectangles `trilab --print-layout` prints:
#   framebuffer W H
#   view X Y W H
#   window "TITLE" X Y W H      (one per visible window)
# Every window and the view lie inside the framebuffer; no two windows overlap, and no window
# overlaps the view, except the dialogs named in DIALOGS (they float over the view and only
# have to lie inside); every title in REQUIRE is present.
#
# cmake -DTRILAB=path/to/trilab -DSIZE=WxH -DSCALE=S [-DARGS="more;arguments"]
#       [-DDIALOGS="Title;Title"] [-DREQUIRE="Title;Title"] -P viewer_layout_check.cmake
# cmake -DLAYOUT_FILE=printed.txt ... -P viewer_layout_check.cmake   (check a saved printout)
cmake_minimum_required(VERSION 3.19)

if(DEFINED LAYOUT_FILE)
    file(READ "${LAYOUT_FILE}" out)
else()
    # The screen is as large as the largest window tested (a smaller one would also work).
    execute_process(
        COMMAND xvfb-run -a -s "-screen 0 2560x1440x24" "${TRILAB}" --size ${SIZE}
                --ui-scale ${SCALE} --frames 4 --print-layout ${ARGS}
        OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
    if(NOT rc EQUAL 0)
        message(FATAL_ERROR "trilab failed (${rc}):\n${out}\n${err}")
    endif()
endif()

if(NOT out MATCHES "framebuffer ([0-9]+) ([0-9]+)")
    message(FATAL_ERROR "no 'framebuffer W H' line in:\n${out}")
endif()
set(fb_w ${CMAKE_MATCH_1})
set(fb_h ${CMAKE_MATCH_2})
if(DEFINED SIZE AND NOT "${fb_w}x${fb_h}" STREQUAL "${SIZE}")
    message(FATAL_ERROR "framebuffer ${fb_w}x${fb_h}, asked for ${SIZE}")
endif()

set(names "")
set(rects "")
set(dialog_flags "")
string(REGEX MATCHALL "(view|window \"[^\"\n]*\") -?[0-9]+ -?[0-9]+ -?[0-9]+ -?[0-9]+" lines
       "${out}")
foreach(line IN LISTS lines)
    string(REGEX MATCH "^(view|window \"([^\"\n]*)\") (-?[0-9]+) (-?[0-9]+) (-?[0-9]+) (-?[0-9]+)$"
           m "${line}")
    if(CMAKE_MATCH_1 STREQUAL "view")
        set(title "(the view)")
    else()
        set(title "${CMAKE_MATCH_2}")
    endif()
    list(APPEND names "${title}")
    list(APPEND rects "${CMAKE_MATCH_3}:${CMAKE_MATCH_4}:${CMAKE_MATCH_5}:${CMAKE_MATCH_6}")
    if(title IN_LIST DIALOGS)
        list(APPEND dialog_flags 1)
    else()
        list(APPEND dialog_flags 0)
    endif()
endforeach()
list(LENGTH names n)
if(n LESS 2)
    message(FATAL_ERROR "no windows in the printout:\n${out}")
endif()
foreach(title IN LISTS REQUIRE)
    if(NOT title IN_LIST names)
        message(FATAL_ERROR "no window \"${title}\" in:\n${out}")
    endif()
endforeach()

set(problems "")
math(EXPR last "${n} - 1")
foreach(i RANGE ${last})
    list(GET names ${i} a_name)
    list(GET rects ${i} a)
    string(REPLACE ":" ";" a "${a}")
    list(GET a 0 ax)
    list(GET a 1 ay)
    list(GET a 2 aw)
    list(GET a 3 ah)
    math(EXPR ar "${ax} + ${aw}")
    math(EXPR ab "${ay} + ${ah}")
    if(ax LESS 0 OR ay LESS 0 OR aw LESS 0 OR ah LESS 0 OR ar GREATER fb_w OR ab GREATER fb_h)
        string(APPEND problems "\"${a_name}\" (${ax} ${ay} ${aw} ${ah}) leaves the framebuffer ${fb_w} x ${fb_h}\n")
    endif()
    list(GET dialog_flags ${i} a_dialog)
    if(a_dialog OR i EQUAL last)
        continue()
    endif()
    math(EXPR first "${i} + 1")
    foreach(j RANGE ${first} ${last})
        list(GET dialog_flags ${j} b_dialog)
        if(b_dialog)
            continue()
        endif()
        list(GET names ${j} b_name)
        list(GET rects ${j} b)
        string(REPLACE ":" ";" b "${b}")
        list(GET b 0 bx)
        list(GET b 1 by)
        list(GET b 2 bw)
        list(GET b 3 bh)
        math(EXPR br "${bx} + ${bw}")
        math(EXPR bb "${by} + ${bh}")
        # Overlap: both intervals intersect with positive length (touching edges is fine).
        if(ax LESS br AND bx LESS ar AND ay LESS bb AND by LESS ab AND aw GREATER 0 AND
           ah GREATER 0 AND bw GREATER 0 AND bh GREATER 0)
            string(APPEND problems "\"${a_name}\" (${ax} ${ay} ${aw} ${ah}) overlaps \"${b_name}\" (${bx} ${by} ${bw} ${bh})\n")
        endif()
    endforeach()
endforeach()

if(NOT problems STREQUAL "")
    message(FATAL_ERROR "layout rule broken:\n${problems}printout:\n${out}")
endif()
message(STATUS "layout ok: ${n} rectangles in ${fb_w} x ${fb_h}")
