# tumble_tool(NAME SOURCES ... MAIN main.cpp [LIBS ...] [PRIVATE_LIBS ...])
#
# An offline tool in tools/<NAME>/ (ARCHITECTURE.md: tools link runtime
# modules, never the reverse). Makes two targets:
#
#   tumble_tool_<NAME>  a static library of SOURCES, so tests can drive the
#                       tool's code in process;
#   tumble-<NAME>       the program, build/bin/tumble-<NAME>, from MAIN.
#
# `tumble NAME ARGS...` runs build/bin/tumble-NAME ARGS... (the tumble binary
# looks for tumble-<command> beside itself when the command is not one of its
# own; tools/README.md). The library's include root holds a single link
# tools/<NAME> -> the tool's folder, so code says #include "tools/NAME/x.h"
# and nothing else of the source tree becomes visible. No runtime module
# links a tool library, so runtime code cannot include tools/ (a ModuleRules
# test checks it).
function(tumble_tool NAME)
  cmake_parse_arguments(ARG "" "MAIN" "SOURCES;LIBS;PRIVATE_LIBS" ${ARGN})
  set(root ${CMAKE_BINARY_DIR}/include/tool_${NAME})
  file(MAKE_DIRECTORY ${root}/tools)
  if(NOT EXISTS ${root}/tools/${NAME})
    file(CREATE_LINK ${CMAKE_SOURCE_DIR}/tools/${NAME} ${root}/tools/${NAME} SYMBOLIC)
  endif()
  add_library(tumble_tool_${NAME} STATIC ${ARG_SOURCES})
  target_include_directories(tumble_tool_${NAME} PUBLIC $<BUILD_INTERFACE:${root}>)
  target_link_libraries(tumble_tool_${NAME} PUBLIC ${ARG_LIBS} PRIVATE ${ARG_PRIVATE_LIBS})
  target_compile_features(tumble_tool_${NAME} PUBLIC cxx_std_20)
  add_executable(tumble-${NAME} ${ARG_MAIN})
  target_link_libraries(tumble-${NAME} PRIVATE tumble_tool_${NAME})
endfunction()
