# Runs `tumble run SCENARIO` broken on purpose and passes only when the run
# notices: at least one expectation must fail, and the exit status must be
# 2 (an expectation failed), not 0 (the scenario would pass a broken
# engine), a crash or a start-up failure (1). A NaN that reaches the
# scenario's own script may also raise script errors there (a binding
# refusing a non-finite number: exit status 3); that is the NaN reported,
# so the nan mode accepts 3 when an expectation failed too.
#   MODE=freeze  run --freeze: scripts run, the physics never steps.
#   MODE=nan     run --inject-nan STEP: a body (else a rope or cloth
#                particle, else the script's ode.system state) goes NaN;
#                the output must also say so ("non-finite", or an
#                expectation whose value is nan).
# cmake -DTUMBLE=... -DSCENARIO=base:drop -DMODE=freeze|nan [-DNAN_STEP=10] -P expect_failure.cmake
if(NOT DEFINED NAN_STEP)
  set(NAN_STEP 10)
endif()
if(MODE STREQUAL "freeze")
  set(args --freeze)
elseif(MODE STREQUAL "nan")
  set(args --inject-nan ${NAN_STEP})
else()
  message(FATAL_ERROR "MODE must be freeze or nan, not '${MODE}'")
endif()
execute_process(COMMAND ${TUMBLE} run ${SCENARIO} ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
set(allowed "2")
if(MODE STREQUAL "nan")
  set(allowed "2|3")
endif()
if(NOT rc MATCHES "^(${allowed})$" OR NOT out MATCHES "expectation failed")
  message(FATAL_ERROR "${SCENARIO} ${args}: exit status '${rc}', expected ${allowed} with an expectation failed; "
                      "0 means its expectations pass a world that is broken this way")
endif()
if(MODE STREQUAL "nan" AND NOT "${out}${err}" MATCHES "non-finite|value -?nan|must be a finite number")
  message(FATAL_ERROR "${SCENARIO} ${args}: failed, but nothing in its output reports the NaN")
endif()
