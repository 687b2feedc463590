// Compiles with input's include paths alone: the two tests above fail for
// the rule, not for a broken command.
#include "input/binding.h"
#include "input/input_system.h"
#include "input/overrides_file.h"
