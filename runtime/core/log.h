#pragma once
// Minimal leveled log to stderr. The app may install a sink (the HUD shows
// warnings and errors).
#include <functional>
#include <string>
#include <string_view>

namespace tumble::log {

enum class Level { Debug, Info, Warn, Error };

void setLevel(Level level);
void message(Level level, std::string_view text);
inline void debug(std::string_view t) { message(Level::Debug, t); }
inline void info(std::string_view t) { message(Level::Info, t); }
inline void warn(std::string_view t) { message(Level::Warn, t); }
inline void error(std::string_view t) { message(Level::Error, t); }

/// Extra sink called for every message at or above the current level.
using Sink = std::function<void(Level, std::string_view)>;
void setSink(Sink sink);

}  // namespace tumble::log
