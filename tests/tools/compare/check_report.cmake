# cmake -DEXE=tumble_compare -DREPORT=out.json -P check_report.cmake
#
# Runs `tumble_compare pyramid_20 --quick --report REPORT` and checks that
# the report names the scene, that both engines stepped every step (wall and
# CPU time), that the default Bullet peer sweeps as often per step as Tumble,
# that every figure the issue asks for is present on both sides, that
# Tumble's collision and contact-solver times are there and within the step,
# and that the pyramid did not fall apart in 20 steps (physics, not printed
# text).
file(REMOVE ${REPORT})
execute_process(COMMAND ${EXE} pyramid_20 --quick --no-bullet-default --report ${REPORT}
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "tumble_compare exited with ${rc}: ${err}")
endif()
if(NOT EXISTS ${REPORT})
  message(FATAL_ERROR "no report written at ${REPORT}")
endif()
file(READ ${REPORT} json)

string(JSON scene GET "${json}" scene)
if(NOT scene STREQUAL "pyramid_20")
  message(FATAL_ERROR "report scene is '${scene}', expected pyramid_20")
endif()
string(JSON steps GET "${json}" steps)
string(JSON dt GET "${json}" dt)
string(JSON ratio GET "${json}" ratio_step_ms)
if(NOT steps EQUAL 20)
  message(FATAL_ERROR "--quick ran ${steps} steps, expected 20")
endif()
if(ratio LESS_EQUAL 0)
  message(FATAL_ERROR "ratio_step_ms is ${ratio}, expected > 0")
endif()

# Matched budget: the peer sweeps as often per step as Tumble does.
string(JSON tumbleSweeps GET "${json}" tumble sweeps_per_step)
string(JSON bulletSweeps GET "${json}" bullet sweeps_per_step)
if(NOT tumbleSweeps EQUAL bulletSweeps)
  message(FATAL_ERROR "Bullet sweeps ${bulletSweeps} times per step, Tumble ${tumbleSweeps}: the default peer must match")
endif()
string(JSON cpuRatio GET "${json}" ratio_step_cpu_ms)
if(NOT cpuRatio GREATER 0)
  message(FATAL_ERROR "ratio_step_cpu_ms is ${cpuRatio}, expected > 0")
endif()

foreach(side tumble bullet)
  foreach(field step_ms_median step_ms_p99 step_cpu_ms_median penetration_max_m escaped stack_drift_m substeps iterations
                sweeps_per_step)
    string(JSON value ERROR_VARIABLE missing GET "${json}" ${side} ${field})
    if(missing)
      message(FATAL_ERROR "report lacks ${side}.${field}: ${missing}")
    endif()
  endforeach()
  string(JSON run GET "${json}" ${side} steps_run)
  if(NOT run EQUAL steps)
    message(FATAL_ERROR "${side} stepped ${run} times, expected ${steps}")
  endif()
  string(JSON median GET "${json}" ${side} step_ms_median)
  if(NOT median GREATER 0)
    message(FATAL_ERROR "${side}.step_ms_median is ${median}: the world did not step")
  endif()
  string(JSON cpu GET "${json}" ${side} step_cpu_ms_median)
  if(NOT cpu GREATER 0)
    message(FATAL_ERROR "${side}.step_cpu_ms_median is ${cpu}: a step took no CPU time")
  endif()
  # A resting pyramid of 0.5 m boxes: after 1/3 s nothing may have moved a
  # box sideways by 5 cm or sunk one 5 cm into another.
  string(JSON drift GET "${json}" ${side} stack_drift_m)
  string(JSON pen GET "${json}" ${side} penetration_max_m)
  if(drift GREATER 0.05 OR pen GREATER 0.05)
    message(FATAL_ERROR "${side}: pyramid moved (drift ${drift} m, penetration ${pen} m)")
  endif()
endforeach()
# Tumble's parts of a step (World::setPhaseTiming): the pyramid rests on
# contacts from the first step, so the contact solver ran and took time, and
# each part took no longer than the whole step.
foreach(field collide_ms_median contact_solver_ms_median contact_points_median contact_solver_ns_per_point_substep)
  string(JSON value ERROR_VARIABLE missing GET "${json}" tumble ${field})
  if(missing OR NOT value GREATER 0)
    message(FATAL_ERROR "tumble.${field} is '${value}' ${missing}: expected > 0")
  endif()
endforeach()
string(JSON stepMs GET "${json}" tumble step_ms_median)
string(JSON collideMs GET "${json}" tumble collide_ms_median)
string(JSON solverMs GET "${json}" tumble contact_solver_ms_median)
if(solverMs GREATER stepMs OR collideMs GREATER stepMs)
  message(FATAL_ERROR "a part of Tumble's step took longer than the step: collide ${collideMs} ms, contact solver ${solverMs} ms, step ${stepMs} ms")
endif()
message(STATUS "report ok: tumble/bullet step ratio ${ratio}")
