# cmake -DEXE=tumble_compare -DREPORT=out.json -P check_ragdolls.cmake
#
# Runs `tumble_compare ragdolls_100 --steps 60 --report REPORT` (1 s: the
# dolls fall and land) and checks that both engines built the 1000 joints
# and report joint_error_max_m, and that neither let a joint come apart
# (anchors within 10 cm; Tumble's impulse joint solver within 5 cm).
file(REMOVE ${REPORT})
execute_process(COMMAND ${EXE} ragdolls_100 --steps 60 --no-bullet-default --report ${REPORT}
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "tumble_compare exited with ${rc}: ${err}")
endif()
file(READ ${REPORT} json)
string(JSON joints GET "${json}" joints)
string(JSON bodies GET "${json}" bodies)
if(NOT joints EQUAL 1000 OR NOT bodies EQUAL 1101)
  message(FATAL_ERROR "ragdolls_100 has ${bodies} bodies and ${joints} joints, expected 1101 (with the ground) and 1000")
endif()
foreach(side tumble bullet)
  string(JSON err GET "${json}" ${side} joint_error_max_m)
  if(NOT err GREATER 0 OR err GREATER 0.1)
    message(FATAL_ERROR "${side}.joint_error_max_m is ${err} m: expected a measured value below 0.1 m")
  endif()
endforeach()
string(JSON tumbleErr GET "${json}" tumble joint_error_max_m)
if(tumbleErr GREATER 0.05)
  message(FATAL_ERROR "tumble (impulse joints) opened a joint by ${tumbleErr} m, more than 5 cm")
endif()
message(STATUS "ragdolls_100 ok: joint error tumble ${tumbleErr} m")
