# Script run by the package.consumer test (cmake -P).
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)

function(run)
  execute_process(COMMAND ${ARGV} RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "command failed (${result}): ${ARGV}\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

# The README's embedding example: the first ```cpp block.
file(READ ${README} readme)
string(REGEX MATCH "```cpp\n(.*)```" block "${readme}")
string(REGEX REPLACE "```.*" "" example "${CMAKE_MATCH_1}")
if(NOT example MATCHES "int main")
  message(FATAL_ERROR "no C++ embedding example found in ${README}")
endif()
file(WRITE ${WORK_DIR}/readme_example.cpp "${example}")

run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})

# The installed headers are exactly those docs/ARCHITECTURE.md lists under "Public headers"
# (the first ```text block after that heading), and no solver header is among them.
file(READ ${ARCHITECTURE} architecture)
string(FIND "${architecture}" "## Public headers" start)
string(SUBSTRING "${architecture}" ${start} -1 section)
string(REGEX MATCH "```text\n([^`]*)```" block "${section}")
if(start LESS 0 OR NOT CMAKE_MATCH_1)
  message(FATAL_ERROR "no list of public headers found in ${ARCHITECTURE}")
endif()
string(REGEX MATCHALL "tumble/[a-z_/]+\\.h" documented "${CMAKE_MATCH_1}")
list(SORT documented)
file(GLOB_RECURSE installed RELATIVE ${prefix}/include ${prefix}/include/*)
list(SORT installed)
if(NOT installed STREQUAL documented)
  message(FATAL_ERROR "installed headers differ from the documented public headers:\n"
                      "installed:  ${installed}\ndocumented: ${documented}")
endif()
if(installed MATCHES "tumble/solver/")
  message(FATAL_ERROR "a solver header is installed: ${installed}")
endif()

run(${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR}/build -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_BUILD_TYPE=Release
    "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}" -DREADME_EXAMPLE=${WORK_DIR}/readme_example.cpp
    -DPUBLIC_HEADERS_DIR=${prefix}/include)
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run(${WORK_DIR}/build/consumer)
if(NOT last_output MATCHES "fell 4\\.9")
  message(FATAL_ERROR "consumer printed an unexpected result: ${last_output}")
endif()
message(STATUS "consumer: ${last_output}")
run(${WORK_DIR}/build/readme_example)
if(NOT last_output MATCHES "^[0-9]+\\.[0-9]+ m\n")
  message(FATAL_ERROR "README example printed an unexpected result: ${last_output}")
endif()
