// Must NOT compile with render's include paths: render reads a plain
// snapshot and never the simulation's headers.
#include "render/renderer.h"
#include "physics/world.h"
