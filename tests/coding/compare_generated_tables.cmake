# Regenerates the quantizer tables and compares them byte for byte with the
# committed, normative lib/coding/entropy/quantizer_tables.inc.
# Usage: cmake -DGENERATOR=<exe> -DCOMMITTED=<file> -DOUT=<file> -P compare_generated_tables.cmake
execute_process(COMMAND "${GENERATOR}" OUTPUT_FILE "${OUT}" RESULT_VARIABLE rc ERROR_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "generator failed: ${rc}")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${OUT}" "${COMMITTED}" RESULT_VARIABLE diff)
if(NOT diff EQUAL 0)
  message(FATAL_ERROR "regenerated tables differ from ${COMMITTED}; the committed file is normative "
                      "(a libm difference can change last digits: see generate_quantizer_tables.cpp)")
endif()
