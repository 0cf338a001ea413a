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

# The example plant plug-in, built out of tree from the installed project, flown by the installed
# program's front ends from a scenario file that names the plant (docs/plants.md), on short horizons.
set(plant_plugin ${WORK_DIR}/plant-plugin/inverted_pendulum_plugin.so)
execute_process(COMMAND ${CMAKE_COMMAND} -S ${WORK_DIR}/prefix/share/thetad/examples/pendulum-plugin
    -B ${WORK_DIR}/plant-plugin -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=${BUILD_TYPE}
  RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "configuring the installed example plant plug-in failed (${rc})")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/plant-plugin RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "building the installed example plant plug-in failed (${rc})")
endif()
file(WRITE ${WORK_DIR}/pendulum/pendulum.yaml
  "plant: inverted-pendulum\nplant_settings: {length: 0.8, damping: 0.2}\nduration: 2\n")
# The installed thetad with the plant plug-in loaded, in the folder of the scenario file; `what`
# names the step in the failure's message.
function(fly_plant what)
  execute_process(COMMAND ${WORK_DIR}/prefix/bin/thetad --plugin ${plant_plugin} ${ARGN}
    WORKING_DIRECTORY ${WORK_DIR}/pendulum RESULT_VARIABLE rc OUTPUT_VARIABLE output ERROR_VARIABLE errors)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "the installed thetad did not fly the out-of-tree plant plug-in (${what}, ${rc}):\n${output}${errors}")
  endif()
  set(plant_errors "${errors}" PARENT_SCOPE)
endfunction()
# `key` of the JSON file `file` must be `expected`.
function(expect_json file expected)
  file(READ ${file} text)
  string(JSON value GET "${text}" ${ARGN})
  if(NOT value STREQUAL expected)
    message(FATAL_ERROR "${file}: ${ARGN} is '${value}', not '${expected}'")
  endif()
endfunction()

fly_plant(compare compare --scenario pendulum.yaml --controllers theta-d,sdre,lqr --no-timing --quiet --out compare)
foreach(label theta-d sdre lqr)
  expect_json(${WORK_DIR}/pendulum/compare/${label}.json inverted-pendulum provenance plant)
  expect_json(${WORK_DIR}/pendulum/compare/${label}.json completed status)
  expect_json(${WORK_DIR}/pendulum/compare/${label}.json 2000 controller_samples)
endforeach()

fly_plant(bench bench --scenario pendulum.yaml --controllers theta-d,sdre --duration 0.5 --samples 50 --segments 5
  --repetitions 2 --warmup 0 --cpu -2 --quiet --out bench.json)
expect_json(${WORK_DIR}/pendulum/bench.json inverted-pendulum provenance plant)
expect_json(${WORK_DIR}/pendulum/bench.json completed recording_status)
expect_json(${WORK_DIR}/pendulum/bench.json sdre controllers 1 label)

fly_plant(optimal optimal --scenario pendulum.yaml --controllers sdre,lqr --horizon 1 --cost j --control-interval 0.1
  --no-timing --quiet --out optimal)
expect_json(${WORK_DIR}/pendulum/optimal/optimality.json ON converged)
string(FIND "${plant_errors}" "no Jacobian" found)
if(NOT found EQUAL -1)
  message(FATAL_ERROR "thetad optimal did not use the example plant's Jacobian:\n${plant_errors}")
endif()

# A campaign sweeping the plant's own setting and its initial angle: 2 x 2 cells, 2 controllers.
file(WRITE ${WORK_DIR}/pendulum/sweep.yaml "campaign: pendulum-sweep\nscenarios: [pendulum.yaml]\n"
  "controllers:\n  - {controller: theta-d}\n  - {controller: lqr}\ndraws: {count: 1, base_seed: 1}\n"
  "fixed: {duration_s: 1}\nsweep:\n  grid:\n    plant.length: [0.5, 1.5]\n    initial_state.0: [0.2, 0.4]\n")
fly_plant(campaign campaign run sweep.yaml --no-timing --quiet --out campaign)
find_program(system_python python3 PATHS /usr/bin NO_DEFAULT_PATH)
if(system_python)
  # The database's runs: every one completed, each cell's factors in their own columns.
  execute_process(COMMAND ${system_python} -c "import sqlite3; db = sqlite3.connect('${WORK_DIR}/pendulum/campaign/campaign.sqlite'); print(db.execute('SELECT COUNT(*), SUM(status = ?), COUNT(DISTINCT [plant.length]), COUNT(DISTINCT [initial_state.0]) FROM runs', ('completed',)).fetchone())"
    RESULT_VARIABLE rc OUTPUT_VARIABLE counts ERROR_VARIABLE errors OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(NOT rc EQUAL 0 OR NOT counts STREQUAL "(8, 8, 2, 2)")
    message(FATAL_ERROR "the plant campaign's database holds (runs, completed, lengths, angles) = ${counts}, not "
                        "(8, 8, 2, 2) (${rc}):\n${errors}")
  endif()

  # The plant's figures, where Debian's matplotlib (and what the plotting package imports beside it)
  # is there to draw them: thetad plot runs /usr/bin/python3.
  execute_process(COMMAND ${system_python} -c "import matplotlib, numpy, pandas, scipy" RESULT_VARIABLE no_matplotlib OUTPUT_QUIET ERROR_QUIET)
  if(no_matplotlib EQUAL 0)
    fly_plant(plot plot --in compare --out figures)
    if(NOT EXISTS ${WORK_DIR}/pendulum/figures/states.png OR NOT EXISTS ${WORK_DIR}/pendulum/figures/inputs.png)
      message(FATAL_ERROR "thetad plot drew no states.png and inputs.png of the plant's runs")
    endif()
  endif()
endif()

# The installed Python package loads the same plug-in and flies its plant.
if(PYTHON)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${WORK_DIR}/prefix/${PYTHON_PACKAGE_DIR} PYTHONDONTWRITEBYTECODE=1
      ${PYTHON} -c "import thetad; thetad.load_plugin('${plant_plugin}'); r = thetad.run(plant='inverted-pendulum', controller='sdre', initial_state=[0.2, 0], duration_s=1, summary_only=True); print(r.provenance['plant'], r.status)"
    RESULT_VARIABLE rc OUTPUT_VARIABLE output ERROR_VARIABLE errors OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(NOT rc EQUAL 0 OR NOT output STREQUAL "inverted-pendulum completed")
    message(FATAL_ERROR "the installed Python package did not fly the plant plug-in (${rc}): ${output}\n${errors}")
  endif()
endif()
