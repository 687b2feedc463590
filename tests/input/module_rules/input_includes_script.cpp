// Must NOT compile with input's include paths: input turns SDL events into
// actions and never sees Lua (script uses input, not the other way round).
#include "input/input_system.h"
#include "script/scenario_host.h"
