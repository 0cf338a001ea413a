# Installs the build tree into a scratch prefix, then configures, builds and runs a consumer
# project that knows thetad only through find_package(thetad CONFIG REQUIRED).
file(REMOVE_RECURSE ${WORK_DIR})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix
  RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${rc})")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR}/build
  -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=${BUILD_TYPE} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "configuring the downstream project failed (${rc})")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/build RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "building the downstream project failed (${rc})")
endif()
execute_process(COMMAND ${WORK_DIR}/build/downstream RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the downstream program failed (${rc})")
endif()

# The installed program draws with the installed plotting script, not the source tree's.
execute_process(COMMAND ${WORK_DIR}/prefix/bin/thetad plot --help OUTPUT_VARIABLE help RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the installed thetad plot --help failed (${rc})")
endif()
file(REAL_PATH ${WORK_DIR}/prefix/share/thetad/plot_run.py installed_script)
string(FIND "${help}" "${installed_script}" found)
if(found EQUAL -1)
  message(FATAL_ERROR "the installed thetad does not default to ${installed_script}:\n${help}")
endif()
