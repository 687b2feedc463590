# ctest script: `tools/tumble terrain info MAP --json` prints one JSON object
# on stdout and nothing else, when there is nothing to build.
# cmake -DWRAPPER=tools/tumble -DTUMBLE=build/bin/tumble -DOUT=DIR -P check_wrapper_stdout.cmake
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})
set(map ${OUT}/map.png)
execute_process(COMMAND ${TUMBLE} terrain gen --width 33 --height 17 --seed 3 --out ${map}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "tumble terrain gen failed (${rc}):\n${out}${err}")
endif()

# The wrapper checks packages and runs the build (nothing to do: ctest runs
# after the build), then runs the command.
execute_process(COMMAND ${WRAPPER} terrain info ${map} --json
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "stdout:\n${out}\nstderr:\n${err}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "tools/tumble terrain info failed with exit code ${rc}")
endif()
string(JSON width ERROR_VARIABLE json_error GET "${out}" width)
if(json_error)
  message(FATAL_ERROR "stdout is not a JSON object (${json_error})")
endif()
string(JSON height GET "${out}" height)
if(NOT width EQUAL 33 OR NOT height EQUAL 17)
  message(FATAL_ERROR "the JSON says ${width} x ${height} samples; the map has 33 x 17")
endif()
# One line: the object and its newline, nothing before or after it.
string(REGEX MATCHALL "\n" newlines "${out}")
list(LENGTH newlines lines)
if(NOT lines EQUAL 1 OR NOT out MATCHES "^{.*}\n$")
  message(FATAL_ERROR "stdout holds more than the command's one line of JSON")
endif()
