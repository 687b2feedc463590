// Must NOT compile with particles' include paths: particles may not see
// physics (attachment goes through an opaque anchor the app resolves).
#include "particles/particle_system.h"
#include "physics/world.h"
