#pragma once
// Result<T>: a value or a message for the user. Used for bad files and bad mod
// data (STYLE.md); programmer mistakes use TUMBLE_ASSERT instead. The message
// should name the file, the field and what would be valid.
#include <string>
#include <utility>
#include <variant>

#include "core/assert.h"

namespace tumble {

struct Error {
  std::string message;
};

template <typename T>
class [[nodiscard]] Result {
 public:
  Result(T value) : m_data(std::move(value)) {}  // NOLINT: implicit by design
  Result(Error error) : m_data(std::move(error)) {}  // NOLINT

  bool ok() const { return std::holds_alternative<T>(m_data); }
  explicit operator bool() const { return ok(); }

  T& value() {
    TUMBLE_ASSERT(ok(), "Result::value() on an error. Check ok() first.");
    return std::get<T>(m_data);
  }
  const T& value() const {
    TUMBLE_ASSERT(ok(), "Result::value() on an error. Check ok() first.");
    return std::get<T>(m_data);
  }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  T& operator*() { return value(); }

  const std::string& error() const {
    TUMBLE_ASSERT(!ok(), "Result::error() on a value. Check ok() first.");
    return std::get<Error>(m_data).message;
  }

 private:
  std::variant<T, Error> m_data;
};

/// Result of an operation with no value.
struct Ok {};
using Status = Result<Ok>;

inline Error makeError(std::string message) { return Error{std::move(message)}; }

}  // namespace tumble
