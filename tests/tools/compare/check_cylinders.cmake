# cmake -DEXE=tumble_compare -DREPORT=out.json -P check_cylinders.cmake
#
# Runs `tumble_compare cylinders_400 --steps 120 --report REPORT` (2 s: the
# 1 cm gaps close and the columns settle) and checks that both engines
# built the 400 cylinders and saw them touch (an overlap above zero: a
# world that did not step, or cylinders that did not collide, sees none),
# and that Tumble's columns stand: a column of four that tips moves its
# top by tens of centimetres, a standing one by a fraction of a millimetre,
# so 1 cm of sideways drift separates the two; its deepest overlap stays
# below 1 cm (twice the solver's 5 mm slop) and no body went non-finite.
file(REMOVE ${REPORT})
execute_process(COMMAND ${EXE} cylinders_400 --steps 120 --no-bullet-default --report ${REPORT}
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "tumble_compare exited with ${rc}: ${err}")
endif()
file(READ ${REPORT} json)
string(JSON bodies GET "${json}" bodies)
if(NOT bodies EQUAL 401)
  message(FATAL_ERROR "cylinders_400 has ${bodies} bodies, expected 401 (with the ground)")
endif()
foreach(side tumble bullet)
  string(JSON pen GET "${json}" ${side} penetration_max_m)
  if(NOT pen GREATER 0)
    message(FATAL_ERROR "${side}: no overlap was ever seen (${pen} m): the cylinders did not touch")
  endif()
endforeach()
string(JSON drift GET "${json}" tumble stack_drift_m)
string(JSON pen GET "${json}" tumble penetration_max_m)
string(JSON nan GET "${json}" tumble nan_events)
if(NOT drift LESS 0.01 OR NOT pen LESS 0.01 OR NOT nan EQUAL 0)
  message(FATAL_ERROR "tumble: drift ${drift} m, overlap ${pen} m, ${nan} non-finite bodies: expected columns that "
                      "stand (drift and overlap below 1 cm) and none")
endif()
message(STATUS "cylinders_400 ok: tumble drift ${drift} m, overlap ${pen} m")
