#pragma once
// Exact-bits serialisation of plain data (snapshots of a running scene):
// values are copied as their raw bytes, so floats come back bit for bit.
// Only for plain values (kBitwise: no pointers or owned memory; Eigen's
// fixed-size vectors and quaternions count), in the byte order of the machine that
// wrote them (a snapshot is read by the same build; its header says which).
// ByteReader never reads past the end: a short or damaged buffer makes
// ok() false and every later read a no-op returning zeros.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace tumble {

/// Types whose bytes are their value: trivially copyable ones, and types
/// with no destructor of their own (Eigen's fixed-size matrices, structs of
/// them) that are not pointers.
template <typename T>
inline constexpr bool kBitwise =
    std::is_trivially_copyable_v<T> || (std::is_trivially_destructible_v<T> && !std::is_pointer_v<T>);

/// Whether bool members read back as raw bytes hold 0 or 1. Read as bytes:
/// loading a bool whose byte is anything else is undefined, so damaged or
/// hand-made bytes are checked with this before any such bool is used.
template <typename... B>
bool validBools(const B&... b) {
  static_assert((std::is_same_v<B, bool> && ...));
  auto one = [](const bool& v) {
    unsigned char c;
    std::memcpy(&c, &v, 1);
    return c <= 1;
  };
  return (one(b) && ...);
}

/// Whether a restored list of slot indices names no slot twice (free lists,
/// orders: a repeat would hand one slot out twice).
inline bool allDistinct(std::vector<std::uint32_t> v) {
  std::sort(v.begin(), v.end());
  return std::adjacent_find(v.begin(), v.end()) == v.end();
}

class ByteWriter {
 public:
  template <typename T>
  void pod(const T& v) {
    static_assert(kBitwise<T>);
    m_bytes.append(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  template <typename T>
  void vec(const std::vector<T>& v) {
    static_assert(kBitwise<T>);
    pod(std::uint64_t(v.size()));
    if (!v.empty()) m_bytes.append(reinterpret_cast<const char*>(v.data()), sizeof(T) * v.size());
  }
  void text(const std::string& s) {
    pod(std::uint64_t(s.size()));
    m_bytes.append(s);
  }
  const std::string& bytes() const { return m_bytes; }
  std::string take() { return std::move(m_bytes); }

 private:
  std::string m_bytes;
};

class ByteReader {
 public:
  explicit ByteReader(const std::string& bytes) : m_data(bytes.data()), m_size(bytes.size()) {}
  template <typename T>
  T pod() {
    static_assert(kBitwise<T>);
    T v{};
    if (!take(sizeof(T))) return v;
    std::memcpy(static_cast<void*>(&v), m_data + m_pos - sizeof(T), sizeof(T));
    return v;
  }
  template <typename T>
  void pod(T& out) { out = pod<T>(); }
  /// A vector of at most maxCount elements (more: not ok).
  template <typename T>
  std::vector<T> vec(std::size_t maxCount) {
    static_assert(kBitwise<T>);
    const std::uint64_t n = pod<std::uint64_t>();
    std::vector<T> v;
    if (!m_ok || n > maxCount || n * sizeof(T) > m_size - m_pos) {
      m_ok = false;
      return v;
    }
    v.resize(std::size_t(n));
    if (n) std::memcpy(static_cast<void*>(v.data()), m_data + m_pos, sizeof(T) * n);
    m_pos += sizeof(T) * n;
    return v;
  }
  std::string text(std::size_t maxBytes) {
    const std::uint64_t n = pod<std::uint64_t>();
    if (!m_ok || n > maxBytes || n > m_size - m_pos) {
      m_ok = false;
      return {};
    }
    std::string s(m_data + m_pos, std::size_t(n));
    m_pos += std::size_t(n);
    return s;
  }
  bool ok() const { return m_ok; }
  bool atEnd() const { return m_pos == m_size; }
  std::size_t position() const { return m_pos; }
  /// Bytes not read yet: a count read from the bytes is checked against
  /// this before anything is allocated for it.
  std::size_t remaining() const { return m_size - m_pos; }
  /// The bytes read since position `start` (a part to read again later).
  std::string bytesFrom(std::size_t start) const { return std::string(m_data + start, m_pos - start); }

 private:
  bool take(std::size_t n) {
    if (!m_ok || n > m_size - m_pos) {
      m_ok = false;
      return false;
    }
    m_pos += n;
    return true;
  }
  const char* m_data;
  std::size_t m_size, m_pos = 0;
  bool m_ok = true;
};

}  // namespace tumble
