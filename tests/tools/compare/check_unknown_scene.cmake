# cmake -DEXE=tumble_compare -P check_unknown_scene.cmake
# An unknown scene exits with status 1 and names the valid scenes.
execute_process(COMMAND ${EXE} no_such_scene RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT rc EQUAL 1)
  message(FATAL_ERROR "unknown scene: exit status ${rc}, expected 1")
endif()
foreach(name boxes_3000 boxes_3000_stacked pyramid_20 highspeed_1000)
  string(FIND "${err}" "${name}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "unknown-scene message does not list '${name}': ${err}")
  endif()
endforeach()
