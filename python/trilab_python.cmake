# The Python module `trilab` (docs/python.md), built with pybind11 from Debian (pybind11-dev)
# for Debian's own python3 (/usr/bin/python3, the interpreter python3-numpy serves; the
# top-level CMakeLists.txt chooses it unless -DPython3_EXECUTABLE=... says otherwise).
# Included from the top-level CMakeLists.txt once pybind11 is found; sets
# TRILAB_PYTHON_MODULE_DIR, the module's directory in the build (the tests' PYTHONPATH).
pybind11_add_module(trilab_python MODULE NO_EXTRAS
                    ${CMAKE_CURRENT_LIST_DIR}/module.cpp ${CMAKE_CURRENT_LIST_DIR}/mesh_arrays.cpp
                    ${CMAKE_CURRENT_LIST_DIR}/operations.cpp
                    ${CMAKE_CURRENT_LIST_DIR}/python_progress.cpp
                    ${CMAKE_CURRENT_LIST_DIR}/session.cpp ${CMAKE_CURRENT_LIST_DIR}/show.cpp)
target_link_libraries(trilab_python PRIVATE trilab_cli_commands trilab_app)
target_compile_options(trilab_python PRIVATE ${TRILAB_WARNINGS})
# Only PyInit_trilab is exported: the static libraries' symbols stay inside the module.
target_link_options(trilab_python PRIVATE "LINKER:--exclude-libs,ALL")
set(TRILAB_PYTHON_MODULE_DIR ${CMAKE_BINARY_DIR}/python)
set_target_properties(trilab_python PROPERTIES OUTPUT_NAME trilab
                      LIBRARY_OUTPUT_DIRECTORY ${TRILAB_PYTHON_MODULE_DIR})
