#include "core/log.h"

#include <cstdio>

namespace tumble::log {
namespace {
Level g_level = Level::Info;
Sink g_sink;
const char* prefix(Level l) {
  switch (l) {
    case Level::Debug: return "debug";
    case Level::Info: return "info";
    case Level::Warn: return "warning";
    case Level::Error: return "error";
  }
  return "?";
}
}  // namespace

void setLevel(Level level) { g_level = level; }
void setSink(Sink sink) { g_sink = std::move(sink); }

void message(Level level, std::string_view text) {
  if (level < g_level) return;
  std::fprintf(stderr, "tumble: %s: %.*s\n", prefix(level), int(text.size()), text.data());
  if (g_sink) g_sink(level, text);
}

}  // namespace tumble::log
