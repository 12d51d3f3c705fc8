# cmake -DSOURCE_DIR=... -DOUT=... -P git_describe.cmake
# Writes OUT defining SHADOWBENCH_GIT_DESCRIBE (`git describe --tags --always
# --dirty`, or "unknown" outside a git checkout), touching it only when the
# text changes so that nothing rebuilds when the commit did not.
execute_process(COMMAND git -C "${SOURCE_DIR}" describe --tags --always --dirty
                OUTPUT_VARIABLE describe RESULT_VARIABLE rc
                OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
if(NOT rc EQUAL 0 OR describe STREQUAL "")
  set(describe "unknown")
endif()
set(content "#define SHADOWBENCH_GIT_DESCRIBE \"${describe}\"\n")
set(old "")
if(EXISTS "${OUT}")
  file(READ "${OUT}" old)
endif()
if(NOT old STREQUAL content)
  file(WRITE "${OUT}" "${content}")
endif()
