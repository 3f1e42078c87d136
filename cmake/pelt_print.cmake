# cmake -DPELT=path/to/pelt -DARGS="a|b" -DOUT=file [-DGZIP=ON] -P pelt_print.cmake
# Runs pelt with ARGS ('|'-separated), its output into OUT (and OUT.gz with
# GZIP, as Debian installs manual pages). Fails the build if pelt fails.
string(REPLACE "|" ";" ARGS "${ARGS}")
execute_process(COMMAND ${PELT} ${ARGS} OUTPUT_FILE ${OUT}.tmp RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  file(REMOVE ${OUT}.tmp)
  message(FATAL_ERROR "'${PELT} ${ARGS}' failed: ${rc}")
endif()
file(RENAME ${OUT}.tmp ${OUT})
if(GZIP)
  find_program(GZIP_EXECUTABLE gzip REQUIRED)
  execute_process(COMMAND ${GZIP_EXECUTABLE} -9nc ${OUT} OUTPUT_FILE ${OUT}.gz RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "gzip ${OUT} failed: ${rc}")
  endif()
endif()
