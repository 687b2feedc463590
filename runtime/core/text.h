#pragma once
// Small text helpers for messages about user data.
#include <cstddef>
#include <string>

namespace tumble {

/// `text` for a message, cut to `maxChars` with a note of how much was cut:
/// a name, version or path from a user's file can be any length, and a
/// message quoting it whole (300 000 characters) helps nobody.
inline std::string clipped(const std::string& text, std::size_t maxChars = 80) {
  if (text.size() <= maxChars) return text;
  return text.substr(0, maxChars) + "... (" + std::to_string(text.size()) + " characters)";
}

}  // namespace tumble
