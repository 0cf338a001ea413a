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
execute_process(COMMAND ${WORK_DIR}/build/downstream ${WORK_DIR}/prefix/share/thetad/scenarios/scenario-1.yaml
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the downstream program failed (${rc})")
endif()

# The installed program draws with the installed plotting script, not the source tree's.
execute_process(COMMAND ${WORK_DIR}/prefix/bin/thetad plot --help OUTPUT_VARIABLE help RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the installed thetad plot --help failed (${rc})")
endif()
file(REAL_PATH ${WORK_DIR}/prefix/share/thetad/scripts/plot_run.py installed_script)
string(FIND "${help}" "${installed_script}" found)
if(found EQUAL -1)
  message(FATAL_ERROR "the installed thetad does not default to ${installed_script}:\n${help}")
endif()

# The installed program finds its installed scenarios by name, and says which file it flew.
execute_process(COMMAND ${WORK_DIR}/prefix/bin/thetad run --scenario scenario-1 --controller theta-d --duration 0.2
    --summary-only --quiet --out ${WORK_DIR}/run
  RESULT_VARIABLE rc OUTPUT_VARIABLE output ERROR_VARIABLE errors)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the installed thetad run --scenario scenario-1 failed (${rc}):\n${output}${errors}")
endif()
file(READ ${WORK_DIR}/run/theta-d.json result)
string(JSON flown GET "${result}" provenance scenario file)
file(REAL_PATH ${WORK_DIR}/prefix/share/thetad/scenarios/scenario-1.yaml installed_scenario)
file(REAL_PATH ${flown} flown)
if(NOT flown STREQUAL installed_scenario)
  message(FATAL_ERROR "the installed thetad flew ${flown}, not the installed ${installed_scenario}")
endif()
foreach(installed share/doc/thetad/model.md share/thetad/scripts/plot_run.py share/thetad/scripts/thetad_plots/run.py
    share/thetad/scripts/thetad_plots/style.py share/thetad/scenarios/scenario-2.yaml)
  if(NOT EXISTS ${WORK_DIR}/prefix/${installed})
    message(FATAL_ERROR "cmake --install did not install ${installed}")
  endif()
endforeach()

# A plug-in built out of tree from the installed example project, flown by the installed thetad.
execute_process(COMMAND ${CMAKE_COMMAND} -S ${WORK_DIR}/prefix/share/thetad/examples/pid-plugin
    -B ${WORK_DIR}/plugin -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=${BUILD_TYPE}
  RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "configuring the installed example plug-in failed (${rc})")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/plugin RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "building the installed example plug-in failed (${rc})")
endif()
execute_process(COMMAND ${WORK_DIR}/prefix/bin/thetad --plugin ${WORK_DIR}/plugin/example_pid_plugin.so run
    --scenario scenario-1 --controller example-pid-plugin --duration 5 --summary-only --quiet --out ${WORK_DIR}/run
  RESULT_VARIABLE rc OUTPUT_VARIABLE output ERROR_VARIABLE errors)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the installed thetad did not fly the out-of-tree plug-in (${rc}):\n${output}${errors}")
endif()

# The installed Python package, from the prefix alone: PYTHONPATH names its folder (docs/python.md),
# and it flies the installed scenario by name.
if(PYTHON)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${WORK_DIR}/prefix/${PYTHON_PACKAGE_DIR} PYTHONDONTWRITEBYTECODE=1
      ${PYTHON} -c "import thetad; r = thetad.run('scenario-1', 'theta-d', duration=0.2, summary_only=True); print(thetad.__file__); print(r.provenance['scenario']['file']); print(r.status)"
    RESULT_VARIABLE rc OUTPUT_VARIABLE output ERROR_VARIABLE errors OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "the installed thetad Python package failed (${rc}):\n${output}${errors}")
  endif()
  string(REPLACE "\n" ";" lines "${output}")
  list(GET lines 0 module)
  list(GET lines 1 flown)
  list(GET lines 2 status)
  file(REAL_PATH ${WORK_DIR}/prefix prefix)
  file(REAL_PATH ${module} module)
  string(FIND "${module}" "${prefix}/${PYTHON_PACKAGE_DIR}/thetad/" found)
  if(NOT found EQUAL 0)
    message(FATAL_ERROR "python imported ${module}, not the installed package under ${prefix}/${PYTHON_PACKAGE_DIR}")
  endif()
  file(REAL_PATH ${flown} flown)
  if(NOT flown STREQUAL installed_scenario OR NOT status STREQUAL "completed")
    message(FATAL_ERROR "the installed Python package flew ${flown} (${status}), not the installed ${installed_scenario}")
  endif()
endif()
