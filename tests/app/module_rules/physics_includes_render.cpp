// Must NOT compile with physics' include paths: physics may not see render.
#include "physics/world.h"
#include "render/renderer.h"
