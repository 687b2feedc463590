// Compiles with physics' include paths: the control case for the rule test.
#include "physics/world.h"
int main() { return tumble::physics::World().bodyCount(); }
