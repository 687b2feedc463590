# cmake -DEXE=tumble_compare -DREPORT=out.json -P check_terrain_rays.cmake
#
# Runs `tumble_compare terrain_rays --quick` and checks that both engines cast
# every ray, and that Tumble's height-field ray casts agree with Bullet's
# btHeightfieldTerrainShape on the same triangles: no ray hits in one engine
# only, and no hit distance differs by more than 1 mm.
file(REMOVE ${REPORT})
execute_process(COMMAND ${EXE} terrain_rays --quick --report ${REPORT}
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "tumble_compare exited with ${rc}: ${err}")
endif()
file(READ ${REPORT} json)
string(JSON rays GET "${json}" rays)
foreach(side tumble bullet bullet_accelerated)
  string(JSON hits GET "${json}" ${side} hits)
  string(JSON seconds GET "${json}" ${side} seconds)
  if(hits LESS 1000 OR NOT seconds GREATER 0)
    message(FATAL_ERROR "${side}: ${hits} hits of ${rays} rays in ${seconds} s")
  endif()
endforeach()
foreach(which agreement agreement_accelerated)
  string(JSON only GET "${json}" ${which} rays_hit_in_one_only)
  string(JSON differ GET "${json}" ${which} rays_distance_differs)
  if(NOT only EQUAL 0 OR NOT differ EQUAL 0)
    message(FATAL_ERROR "${which}: ${only} rays hit in one engine only, ${differ} hit at distances > 1 mm apart")
  endif()
endforeach()
string(JSON ratio GET "${json}" ratio_time_accelerated)
message(STATUS "terrain rays agree; time ratio against Bullet with its accelerator ${ratio}")
