# Smoke test of the viewer under a virtual X server: three frames of the default model and a
# screenshot, exit status 0. Included from tests/CMakeLists.txt when the viewer is built.
if(TARGET trilab)
    add_test(NAME viewer_smoke
             COMMAND xvfb-run -a -s "-screen 0 1280x800x24" $<TARGET_FILE:trilab> --frames 3
                     --screenshot ${CMAKE_CURRENT_BINARY_DIR}/viewer_smoke.png)
endif()
