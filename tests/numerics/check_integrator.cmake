# ctest script: the world's integrator is chosen by the scenario field
# (springs.lua says "sdirk2"), --integrator overrides it, the run report's
# `integrator` says which ran, and an unknown name lists the valid ones.
# cmake -DDRIVER=... -DOUT=... -P check_integrator.cmake
file(MAKE_DIRECTORY ${OUT})

function(run_and_check args expected)
  execute_process(COMMAND ${DRIVER} run base:springs --seconds 0.5 ${args} --report ${OUT}/r.json
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  file(READ ${OUT}/r.json json)
  if(NOT json MATCHES "\"integrator\": *\"${expected}\"")
    message(FATAL_ERROR "run base:springs ${args}: report integrator is not ${expected}:\n${json}")
  endif()
  message(STATUS "run base:springs ${args}: integrator ${expected}, exit ${rc}")
endfunction()

run_and_check("" "sdirk2")
run_and_check("--integrator;rk4" "rk4")
run_and_check("--integrator;trapezoid" "heun")

execute_process(COMMAND ${DRIVER} run base:springs --integrator rk5
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 1)
  message(FATAL_ERROR "--integrator rk5: exit ${rc}, expected 1")
endif()
foreach(name symplectic_euler euler heun rk4 verlet implicit_euler implicit_midpoint sdirk2)
  if(NOT "${out}${err}" MATCHES "${name}")
    message(FATAL_ERROR "--integrator rk5: the message does not list ${name}:\n${out}${err}")
  endif()
endforeach()
message(STATUS "--integrator rk5 refused with the valid names")
