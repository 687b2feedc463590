// The scenario fuzzer: every Lua API function with random values. The fuzz
// input is a program for scenario_driver.lua (read that first): it picks
// functions of every module the sandbox offers, methods of what they
// returned, and example blocks of docs/lua-api.md, and calls them with
// numbers (NaN, inf, huge), strings (huge, paths outside the mod), tables
// (from the docs' examples, changed; with hostile metamethods), callbacks,
// nil and the objects earlier calls returned. Each input is a fresh
// headless scene (as `tumble run` makes it): on_start, 8 fixed steps,
// on_finish. The engine may refuse any call with a Lua error; it must not
// crash, abort, hang, leak or hit undefined behaviour.
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>
#include <vector>

#include "fuzz_scene.h"

namespace {

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

bool identStart(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
bool ident(char c) { return identStart(c) || (c >= '0' && c <= '9'); }

// A Lua string literal holding any bytes (decimal escapes).
std::string quoted(const std::string& bytes) {
  std::string out = "\"";
  for (unsigned char c : bytes) {
    if (ident(char(c)) || c == ' ' || c == ':' || c == '.' || c == ',') {
      out += char(c);
    } else {
      char escape[5];
      std::snprintf(escape, sizeof escape, "\\%03u", unsigned(c));  // three digits: a digit may follow
      out += escape;
    }
  }
  return out + "\"";
}

std::string listOf(const char* name, const std::set<std::string>& items) {
  std::string out = "local " + std::string(name) + " = {";
  for (const std::string& s : items) out += quoted(s) + ",\n";
  return out + "}\n";
}

// The pools the driver draws from, read from docs/lua-api.md once.
std::string docPools() {
  const std::string doc = readFile(std::string(TUMBLE_SOURCE_DIR) + "/docs/lua-api.md");
  if (doc.empty()) std::abort();
  std::set<std::string> keys, words, methods, tables, examples;
  for (std::size_t i = 0; i < doc.size(); ++i) {
    const char c = doc[i];
    if (c == '`' && i + 1 < doc.size() && identStart(doc[i + 1])) {  // `name`
      std::size_t j = i + 1;
      while (j < doc.size() && ident(doc[j])) ++j;
      if (j < doc.size() && doc[j] == '`') keys.insert(doc.substr(i + 1, j - i - 1));
    } else if (c == '"' && i + 1 < doc.size() && identStart(doc[i + 1])) {  // "word"
      std::size_t j = i + 1;
      while (j < doc.size() && (ident(doc[j]) || doc[j] == ':' || doc[j] == '.')) ++j;
      if (j < doc.size() && doc[j] == '"') words.insert(doc.substr(i + 1, j - i - 1));
    } else if (c == ':' && i > 0 && ident(doc[i - 1]) && i + 1 < doc.size() && identStart(doc[i + 1])) {  // x:method(
      std::size_t j = i + 1;
      while (j < doc.size() && ident(doc[j])) ++j;
      if (j < doc.size() && doc[j] == '(') methods.insert(doc.substr(i + 1, j - i - 1));
    }
  }
  // ```lua blocks, and the balanced {...} constructors inside them.
  for (std::size_t at = doc.find("```lua\n"); at != std::string::npos; at = doc.find("```lua\n", at + 1)) {
    const std::size_t begin = at + 7, end = doc.find("```", begin);
    if (end == std::string::npos) break;
    const std::string block = doc.substr(begin, end - begin);
    examples.insert(block);
    for (std::size_t i = 0; i < block.size(); ++i) {
      if (block[i] != '{') continue;
      int depth = 0;
      for (std::size_t j = i; j < block.size(); ++j) {
        if (block[j] == '{') ++depth;
        if (block[j] == '}' && --depth == 0) {
          tables.insert(block.substr(i, j - i + 1));
          break;
        }
      }
    }
  }
  return listOf("KEYS", keys) + listOf("WORDS", words) + listOf("METHODS", methods) + listOf("TABLES", tables) +
         listOf("EXAMPLES", examples);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string prefix = docPools();
  static const std::string driver = readFile(std::string(TUMBLE_SOURCE_DIR) + "/tools/fuzz/scenario_driver.lua");
  if (driver.empty()) std::abort();
  const std::string source =
      prefix + "local INPUT = " + quoted(std::string(reinterpret_cast<const char*>(data), size)) + "\n" + driver;
  // A smaller instruction budget than the default (50 million per callback)
  // so that an input whose callback loops ends in well under libFuzzer's
  // timeout; the budget's checks are the same.
  tumble::script::VmLimits limits;
  limits.instructionsPerCall = 2'000'000;
  auto scene = tumble::fuzz::sceneFor("driver", source, limits);
  if (!scene) std::abort();  // the driver itself must always load
  tumble::fuzz::runSteps(*scene, 8);
  return 0;
}
