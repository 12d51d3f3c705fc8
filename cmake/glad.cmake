# Generates a glad2 GL 4.5 core loader at build time with Debian's python3-glad.
# --reproducible makes glad use its packaged gl.xml instead of downloading it.
# Debian's python3-glad lives in /usr/bin/python3, which may not be the python3 on PATH.
find_program(SHADOWBENCH_DEBIAN_PYTHON NAMES python3 PATHS /usr/bin NO_DEFAULT_PATH)
if(NOT SHADOWBENCH_DEBIAN_PYTHON)
  set(SHADOWBENCH_DEBIAN_PYTHON ${Python3_EXECUTABLE})
endif()
set(GLAD_OUT ${CMAKE_BINARY_DIR}/glad)
add_custom_command(
  OUTPUT ${GLAD_OUT}/src/gl.c ${GLAD_OUT}/include/glad/gl.h
  COMMAND ${SHADOWBENCH_DEBIAN_PYTHON} -m glad --quiet --api gl:core=4.5
          --extensions GL_KHR_debug --reproducible --out-path ${GLAD_OUT} c
  COMMENT "Generating the glad2 GL 4.5 core loader"
  VERBATIM)
add_library(glad STATIC ${GLAD_OUT}/src/gl.c ${GLAD_OUT}/include/glad/gl.h)
target_include_directories(glad SYSTEM PUBLIC ${GLAD_OUT}/include)
set_target_properties(glad PROPERTIES POSITION_INDEPENDENT_CODE ON)
