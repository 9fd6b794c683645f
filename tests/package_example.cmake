# ctest -R package_example: install the built project into a scratch prefix, build examples/
# against it with find_package(meshquilt) as an outside project would, and run the example.
# Arguments (-D): BUILD_DIR, SOURCE_DIR, WORK_DIR, BASE, SWATCH, BAD_SWATCH (no thin axis).
file(REMOVE_RECURSE ${WORK_DIR})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix
                RESULT_VARIABLE rc OUTPUT_QUIET)
if(rc)
  message(FATAL_ERROR "cmake --install failed (${rc})")
endif()
foreach(f include/meshquilt/meshquilt.h include/meshquilt/decorate.h lib/cmake/meshquilt/meshquiltConfig.cmake bin/meshquilt)
  if(NOT EXISTS ${WORK_DIR}/prefix/${f})
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples -B ${WORK_DIR}/build -G Ninja
                        -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix
                RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "configuring examples/ against the installed package failed (${rc})")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/build RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "building examples/ failed (${rc})")
endif()
execute_process(COMMAND ${WORK_DIR}/build/decorate_example ${BASE} ${SWATCH} ${WORK_DIR}/out.obj 0.5 3
                RESULT_VARIABLE rc OUTPUT_VARIABLE out)
if(rc)
  message(FATAL_ERROR "decorate_example failed (${rc})")
endif()
string(FIND "${out}" "{" brace)
string(SUBSTRING "${out}" ${brace} -1 report)
string(JSON elements GET "${report}" elements)
string(REGEX MATCH "^meshquilt [0-9.]+: ([0-9]+) elements" line "${out}")
if(NOT CMAKE_MATCH_1 EQUAL elements OR elements LESS 20)
  message(FATAL_ERROR "unexpected output: ${out}")
endif()
file(STRINGS ${WORK_DIR}/out.obj groups REGEX "^o element_")
list(LENGTH groups ngroups)
if(NOT ngroups EQUAL elements)
  message(FATAL_ERROR "out.obj has ${ngroups} groups for ${elements} elements")
endif()
# bad input: exit code 2 and a message naming the file
execute_process(COMMAND ${WORK_DIR}/build/decorate_example ${BASE} ${BAD_SWATCH} ${WORK_DIR}/bad.obj
                RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
if(NOT rc EQUAL 2 OR NOT err MATCHES "cube.off.*thin axis" OR EXISTS ${WORK_DIR}/bad.obj)
  message(FATAL_ERROR "bad input: exit ${rc}, '${err}'")
endif()
message(STATUS "examples/ built against the installed package: ${elements} elements")
