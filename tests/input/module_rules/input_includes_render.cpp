// Must NOT compile with input's include paths: render and input are both
// leaves under app; the app passes events and plain data between them.
#include "input/input_system.h"
#include "render/renderer.h"
