// Compiles with particles' include paths alone: core is all it needs.
#include "particles/particle_system.h"
