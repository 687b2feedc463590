// Compiles with app's include paths: the control case for the rule test.
#include "app/paths.h"
int main() { return tumble::app::dataDir().empty() ? 1 : 0; }
