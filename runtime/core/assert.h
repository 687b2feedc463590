#pragma once
// Asserts are for programmer mistakes only; bad user data returns Result.
// The message should say how to fix the mistake.
#include <cstdio>
#include <cstdlib>

#define TUMBLE_ASSERT(cond, msg)                                                   \
  do {                                                                             \
    if (!(cond)) {                                                                 \
      std::fprintf(stderr, "%s:%d: assertion failed: %s\n  %s\n", __FILE__, __LINE__, \
                   #cond, msg);                                                    \
      std::abort();                                                                \
    }                                                                              \
  } while (0)
