#pragma once
// JSON from a file a player or a mod hands over is parsed with a depth
// limit. nlohmann's parser itself is iterative, but serialising (dump, as in
// an error message or a checksum), comparing and copying a value recurse
// once per level, so a file nested 100 000 deep (200 kB of brackets) would
// overflow the stack the first time anything walks it. Deeper input is
// refused while it is parsed, before any of that. Header only: the modules
// that read JSON link nlohmann_json themselves.
#include <nlohmann/json.hpp>

#include <string>
#include <string_view>

#include "core/result.h"

namespace tumble {

/// Parses `text` as JSON nested at most `maxDepth` levels (an object or an
/// array is one level). The error says which: "not valid JSON (...)" or
/// "nested more than N levels deep".
inline Result<nlohmann::json> parseJsonWithDepth(std::string_view text, int maxDepth) {
  struct TooDeep {};
  try {
    nlohmann::json j = nlohmann::json::parse(
        text,
        [maxDepth](int depth, nlohmann::json::parse_event_t, nlohmann::json&) {
          if (depth > maxDepth) throw TooDeep{};
          return true;
        },
        /*allow_exceptions=*/true);
    return j;
  } catch (const TooDeep&) {
    return makeError("nested more than " + std::to_string(maxDepth) + " levels deep");
  } catch (const nlohmann::json::exception& e) {
    return makeError(std::string("not valid JSON (") + e.what() + ")");
  }
}

}  // namespace tumble
