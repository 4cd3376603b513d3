# solver.lane-clone-bits: runs both builds of lane_bits_main.cpp and fails unless they print the
# same trajectory hash.
foreach(build CLONES BASELINE)
  execute_process(COMMAND ${${build}} OUTPUT_VARIABLE hash_${build} RESULT_VARIABLE status
                  OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(NOT status EQUAL 0 OR hash_${build} STREQUAL "")
    message(FATAL_ERROR "${${build}} failed (${status})")
  endif()
endforeach()
if(NOT hash_CLONES STREQUAL hash_BASELINE)
  message(FATAL_ERROR "the lane kernels' copies differ: ${hash_CLONES} (clones) against "
                      "${hash_BASELINE} (baseline alone)")
endif()
message(STATUS "same trajectory hash ${hash_CLONES}")
