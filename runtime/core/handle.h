#pragma once
// Handles with a generation counter (after Box2D's b2BodyId): index into a
// pool plus the generation the slot had when the handle was made. A slot's
// generation increases when it is freed, so a stale handle is detected
// instead of silently reaching a new object. The all-zero handle is null
// (generations start at 1).
#include <cstdint>

namespace tumble {

template <typename Tag>
struct Handle {
  std::uint32_t index = 0;
  std::uint32_t generation = 0;
  bool isNull() const { return generation == 0; }
  friend bool operator==(Handle a, Handle b) = default;
};

}  // namespace tumble
