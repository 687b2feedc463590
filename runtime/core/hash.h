#pragma once
// FNV-1a 64-bit, for the state hash that proves determinism. Hashes the exact
// bytes of the values, so any change in any bit changes the hash.
#include <cstdint>
#include <cstring>
#include <string>

namespace tumble {

class Hasher {
 public:
  void bytes(const void* data, std::size_t size) {
    const auto* p = static_cast<const std::uint8_t*>(data);
    for (std::size_t i = 0; i < size; ++i) {
      m_h ^= p[i];
      m_h *= 0x100000001b3ull;
    }
  }
  template <typename T>
  void value(const T& v) {
    bytes(&v, sizeof(T));
  }
  std::uint64_t digest() const { return m_h; }
  std::string hex() const {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(m_h));
    return buf;
  }

 private:
  std::uint64_t m_h = 0xcbf29ce484222325ull;
};

}  // namespace tumble
