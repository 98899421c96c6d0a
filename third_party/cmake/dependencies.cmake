# Finds every Debian package trilab uses (see third_party/packages.txt) and generates the
# OpenGL 3.3 core loader with glad 2 at build time. Nothing here is vendored source.

find_package(Eigen3 3.3 REQUIRED NO_MODULE)
# Spectra 1.0 (header-only Lanczos eigen solvers): only core/algorithms/spectral.cpp includes it.
find_package(Spectra REQUIRED)
# The installed version string ("2rc10") cannot be compared: never ask for a version.
find_package(tinyobjloader REQUIRED)
# stb (stb_image, stb_image_write) is a compiled library in Debian: link PkgConfig::STB.
find_package(PkgConfig REQUIRED)
pkg_check_modules(STB REQUIRED IMPORTED_TARGET stb)
# zlib: the PNG reader inflates the image data once, bounded, before stb_image decodes it
# (core/io/image_io.cpp), to refuse data that inflates past the declared size.
find_package(ZLIB REQUIRED)
# The core's worker threads (spectral slices), the viewer's job runner and their tests.
find_package(Threads REQUIRED)

if(TRILAB_BUILD_VIEWER)
    find_package(glfw3 3.3 REQUIRED)
    find_package(glm REQUIRED)
    # libimgui-dev ships the GLFW and OpenGL 3 backends inside libimgui.a; imgui.pc pulls in stb.
    pkg_check_modules(IMGUI REQUIRED IMPORTED_TARGET imgui)

    # glad 2: generate the GL 3.3 core loader (and EGL 1.5 for offscreen rendering) into the
    # build tree. --reproducible makes glad use its bundled Khronos XML (no network).
    find_program(GLAD_EXECUTABLE glad REQUIRED)
    set(GLAD_OUT ${CMAKE_BINARY_DIR}/glad)
    add_custom_command(
        OUTPUT ${GLAD_OUT}/src/gl.c ${GLAD_OUT}/include/glad/gl.h
               ${GLAD_OUT}/src/egl.c ${GLAD_OUT}/include/glad/egl.h
        COMMAND ${GLAD_EXECUTABLE} --api "gl:core=3.3,egl=1.5"
                --extensions "EGL_EXT_platform_base,EGL_MESA_platform_surfaceless,EGL_KHR_surfaceless_context,EGL_KHR_create_context"
                --out-path ${GLAD_OUT} --reproducible --quiet c --loader
        COMMENT "Generating the OpenGL 3.3 core loader with glad"
        VERBATIM)
    add_library(glad STATIC ${GLAD_OUT}/src/gl.c ${GLAD_OUT}/src/egl.c)
    target_include_directories(glad SYSTEM PUBLIC ${GLAD_OUT}/include)
    target_link_libraries(glad PUBLIC ${CMAKE_DL_LIBS})
endif()

if(TRILAB_BUILD_TESTS)
    find_package(Catch2 REQUIRED)
endif()

# OpenMesh (Debian libopenmesh-dev), OPTIONAL and benchmark-only: the subdivision, operation,
# fairing and decimation benchmarks compare against it when installed. The product, the tests
# and CI never need it, so it is not in packages.txt.
if(TRILAB_BUILD_TESTS)
    find_package(OpenMesh CONFIG QUIET)
    if(TARGET OpenMeshTools)
        set(TRILAB_OPENMESH_TARGET OpenMeshTools)
    else()
        find_path(OPENMESH_INCLUDE_DIR OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh)
        find_library(OPENMESH_CORE_LIBRARY OpenMeshCore)
        if(OPENMESH_INCLUDE_DIR AND OPENMESH_CORE_LIBRARY)
            add_library(trilab_openmesh INTERFACE)
            target_include_directories(trilab_openmesh SYSTEM INTERFACE ${OPENMESH_INCLUDE_DIR})
            target_link_libraries(trilab_openmesh INTERFACE ${OPENMESH_CORE_LIBRARY})
            set(TRILAB_OPENMESH_TARGET trilab_openmesh)
        endif()
    endif()
    if(TRILAB_OPENMESH_TARGET)
        message(STATUS "OpenMesh found: the benchmarks compare against it")
    else()
        message(STATUS "OpenMesh not found (optional, benchmark only): the benchmarks "
                       "run without the comparison; apt-get install libopenmesh-dev to add it")
    endif()
endif()
