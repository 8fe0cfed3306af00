# Generates the OpenGL 4.5 core loader with Debian's python3-glad (glad 2) at build time:
# no hand-written function pointers, nothing generated committed. Contexts pass their own
# GetProcAddress (EGL or OSMesa) to gladLoadGL.
find_program(GPURT_SYSTEM_PYTHON NAMES python3 PATHS /usr/bin NO_DEFAULT_PATH)
if(NOT GPURT_SYSTEM_PYTHON)
  find_program(GPURT_SYSTEM_PYTHON NAMES python3 REQUIRED)
endif()
set(GLAD_DIR ${CMAKE_BINARY_DIR}/glad)
add_custom_command(
  OUTPUT ${GLAD_DIR}/src/gl.c ${GLAD_DIR}/include/glad/gl.h
  COMMAND ${GPURT_SYSTEM_PYTHON} -m glad --quiet --reproducible --api gl:core=4.5
          --extensions GL_KHR_debug,GL_ARB_texture_barrier --out-path ${GLAD_DIR} c
  COMMENT "Generating the OpenGL 4.5 core loader with glad"
  VERBATIM)
add_library(glad STATIC ${GLAD_DIR}/src/gl.c)
target_include_directories(glad SYSTEM PUBLIC ${GLAD_DIR}/include)
set_target_properties(glad PROPERTIES POSITION_INDEPENDENT_CODE ON)
