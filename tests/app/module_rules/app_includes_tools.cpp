// Must NOT compile with app's include paths: the runtime may not see tools/
// (tools link runtime modules, never the reverse).
#include "app/paths.h"
#include "tools/meshgen/meshgen.h"
