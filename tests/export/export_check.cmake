# The acceptance check of `thetad export` (docs/onboard.md): for each controller, export it with
# check data recorded along a short scenario-I flight, compile the check program standalone (no
# thetad include or library; no exceptions, no RTTI, warnings as errors; its allocator aborts) and
# run it: the exported double step must equal the library's u to 1e-12 (relative R-norm).
# Arguments: THETAD (the program), CXX (the compiler), WORK_DIR.
file(REMOVE_RECURSE ${WORK_DIR})
foreach(spec "theta-d" "lqr" "theta-d-velocity=theta-d:${CMAKE_CURRENT_LIST_DIR}/velocity_feedforward.settings.yaml")
  string(REGEX REPLACE "=.*" "" label "${spec}")
  execute_process(COMMAND ${THETAD} export --controller ${spec} --duration 14 --check-segments 7 --check-samples 40
                          --quiet --out ${WORK_DIR}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "thetad export ${spec} failed (${rc}):\n${out}${err}")
  endif()
  execute_process(COMMAND ${CXX} -std=c++20 -O2 -fno-exceptions -fno-rtti -Wall -Wextra -Wpedantic -Werror
                          -o ${WORK_DIR}/${label}_check ${WORK_DIR}/${label}_check.cpp
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "the exported ${label} does not compile standalone:\n${out}${err}")
  endif()
  execute_process(COMMAND ${WORK_DIR}/${label}_check 1e-12 RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message(STATUS "${out}${err}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "the exported ${label}'s check failed (${rc})")
  endif()
endforeach()
