# The GL side of crowdprof_lib (included from lib/CMakeLists.txt): glad's loader,
# generated at build time, libEGL, OSMesa's header (the library is opened at
# run time: osmesa_context.cpp), and the shaders embedded as
# string literals so that the binary needs no install directory.
#
# Never link libGL or libOpenGL here: they export every gl* symbol, like
# libOSMesa, and an OSMesa context then answers NULL. GL functions come from
# glad, loaded through eglGetProcAddress or OSMesaGetProcAddress.

enable_language(C)

find_program(CROWDPROF_GLAD glad DOC "glad 2 generator (Debian: python3-glad)")
if(CROWDPROF_GLAD)
  set(CROWDPROF_GLAD_COMMAND ${CROWDPROF_GLAD})
else()
  # pip's glad2 installs the module without the script.
  find_package(Python3 REQUIRED COMPONENTS Interpreter)
  set(CROWDPROF_GLAD_COMMAND ${Python3_EXECUTABLE} -m glad)
endif()
find_path(CROWDPROF_EGL_INCLUDE EGL/egl.h REQUIRED)
find_library(CROWDPROF_EGL_LIBRARY EGL REQUIRED)
find_path(CROWDPROF_OSMESA_INCLUDE GL/osmesa.h REQUIRED)
find_path(CROWDPROF_STB_INCLUDE stb/stb_image_write.h REQUIRED)

# GL 4.5 core headers, no extensions: everything crowdprof calls is core in 4.3.
set(CROWDPROF_GLAD_DIR ${CMAKE_CURRENT_BINARY_DIR}/glad)
add_custom_command(
  OUTPUT ${CROWDPROF_GLAD_DIR}/src/gl.c ${CROWDPROF_GLAD_DIR}/include/glad/gl.h
  COMMAND ${CROWDPROF_GLAD_COMMAND} --quiet --reproducible --api gl:core=4.5 --extensions= --out-path
          ${CROWDPROF_GLAD_DIR} c
  COMMENT "Generating the GL loader with glad"
  VERBATIM)
add_library(crowdprof_glad STATIC ${CROWDPROF_GLAD_DIR}/src/gl.c)
target_include_directories(crowdprof_glad SYSTEM PUBLIC $<BUILD_INTERFACE:${CROWDPROF_GLAD_DIR}/include>
  $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/crowdprof>)
set_target_properties(crowdprof_glad PROPERTIES POSITION_INDEPENDENT_CODE ON)

# shaders/*.vert|frag|glsl|comp -> one .cpp of raw string literals (render/shader_sources.h).
file(GLOB CROWDPROF_SHADERS CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/shaders/*.vert ${CMAKE_SOURCE_DIR}/shaders/*.frag
     ${CMAKE_SOURCE_DIR}/shaders/*.glsl ${CMAKE_SOURCE_DIR}/shaders/*.comp)
set(CROWDPROF_EMBEDDED_SHADERS ${CMAKE_CURRENT_BINARY_DIR}/embedded_shaders.cpp)
add_custom_command(
  OUTPUT ${CROWDPROF_EMBEDDED_SHADERS}
  COMMAND ${CMAKE_COMMAND} -DOUTPUT=${CROWDPROF_EMBEDDED_SHADERS} "-DFILES=${CROWDPROF_SHADERS}"
          -DROOT=${CMAKE_SOURCE_DIR} -DHEADER=render/shader_sources.h -DTYPE=EmbeddedShader
          -DFUNCTION=embedded_shaders -P ${CMAKE_SOURCE_DIR}/cmake/embed_files.cmake
  DEPENDS ${CROWDPROF_SHADERS} ${CMAKE_SOURCE_DIR}/cmake/embed_files.cmake
  COMMENT "Embedding shaders"
  VERBATIM)
target_sources(crowdprof_lib PRIVATE ${CROWDPROF_EMBEDDED_SHADERS})

target_include_directories(crowdprof_lib SYSTEM PRIVATE ${CROWDPROF_EGL_INCLUDE} ${CROWDPROF_OSMESA_INCLUDE}
  ${CROWDPROF_STB_INCLUDE})
target_link_libraries(crowdprof_lib PUBLIC crowdprof_glad PRIVATE ${CROWDPROF_EGL_LIBRARY} ${CMAKE_DL_LIBS})
