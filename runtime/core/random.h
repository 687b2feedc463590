#pragma once
// splitmix64 (Steele, Lea, Flood 2014): tiny, fast, statistically good and
// fully specified, so a seed gives the same numbers on every platform (the
// std:: distributions do not). Terrain generators, particles, and the Lua
// random streams' seeding all draw from it.
#include <cstdint>

namespace tumble {

/// Advances `state` and returns the next 64 random bits.
inline std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace tumble
