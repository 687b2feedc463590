# tumble_module(NAME SOURCES ... [PUBLIC_DEPS ...] [PRIVATE_DEPS ...])
#
# Creates the library target tumble_<NAME> for runtime/<NAME>/.
#
# Module rules (ARCHITECTURE.md) are enforced by include roots: every module
# gets a private folder build/include/<NAME>/ that holds a single link
# <NAME> -> runtime/<NAME>. A target sees "core/x.h" or "physics/y.h" only if
# it links that module, so a forbidden include (physics including render,
# say) fails to compile instead of silently creating a dependency.
# tests/module_rules checks that this stays true.
function(tumble_module NAME)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  set(root ${CMAKE_BINARY_DIR}/include/${NAME})
  file(MAKE_DIRECTORY ${root})
  if(NOT EXISTS ${root}/${NAME})
    file(CREATE_LINK ${CMAKE_SOURCE_DIR}/runtime/${NAME} ${root}/${NAME} SYMBOLIC)
  endif()
  add_library(tumble_${NAME} STATIC ${ARG_SOURCES})
  target_include_directories(tumble_${NAME} PUBLIC $<BUILD_INTERFACE:${root}>)
  target_link_libraries(tumble_${NAME} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  target_compile_features(tumble_${NAME} PUBLIC cxx_std_20)
endfunction()
