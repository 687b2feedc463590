#pragma once
// The work a Lua pattern match does, counted before it is done.
//
// Lua's string.find, match, gmatch and gsub run their backtracking matcher
// in C, where the instruction count hook never fires: ("a"):rep(40) matched
// against ("a*"):rep(40) .. "b" takes longer than the universe has. The
// sandbox (pattern_budget.cpp) therefore walks the same search as Lua's
// matcher (the semantics of the Lua 5.4 manual, section 6.4.1: the same
// items, in the same order, with the same captures and the same depth limit)
// counting one unit per step (an item tried at a position, a character a
// balance or back-reference compares), and stops as soon as the count passes
// a cap. The caller charges the count to the script's instruction budget and
// only then lets Lua's own function do the match, which then takes the same
// number of steps: the count bounds it.
//
// A malformed pattern stops the walk where Lua's matcher would raise its
// error, so Lua's function raises it after the same, counted, work.
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace tumble::script {

class PatternCost {
 public:
  /// `cap`: stop counting past this many units.
  PatternCost(std::string_view subject, std::string_view pattern, std::uint64_t cap);

  /// Tries the pattern (from `patternStart`, past a leading '^' the caller
  /// handled) at subject offset `at`. Returns the end offset of the match,
  /// or -1 for no match (also when stopped: check stopped()).
  long long matchAt(std::size_t at, std::size_t patternStart);
  std::uint64_t cost() const { return m_cost; }
  /// True when the cap was passed or the pattern is malformed (Lua's matcher
  /// raises an error at that point).
  bool stopped() const { return m_stopped; }
  /// After a match: a capture was opened and never closed ("(a" matches
  /// "a"); Lua raises "unfinished capture" when it returns the captures.
  bool unfinishedCapture() const {
    for (int i = 0; i < m_level; ++i)
      if (m_capture[i].len == kUnfinished) return true;
    return false;
  }
  /// Adds work done outside the matcher (copying a replacement, ...).
  void add(std::uint64_t units);

 private:
  static constexpr int kMaxCaptures = 32;   // LUA_MAXCAPTURES
  static constexpr int kMaxDepth = 200;     // the matcher's MAXCCALLS
  static constexpr long long kUnfinished = -1, kPosition = -2;
  struct Capture {
    std::size_t init = 0;
    long long len = 0;
  };
  const char* match(const char* s, const char* p);
  const char* maxExpand(const char* s, const char* p, const char* ep);
  const char* minExpand(const char* s, const char* p, const char* ep);
  const char* startCapture(const char* s, const char* p, long long what);
  const char* endCapture(const char* s, const char* p);
  const char* matchBalance(const char* s, const char* p);
  const char* matchBackReference(const char* s, int digit);
  const char* classEnd(const char* p);
  bool singleMatch(const char* s, const char* p, const char* ep);
  bool step();  ///< counts one unit; false once stopped
  void stop() { m_stopped = true; }
  char at(const char* p) const { return p < m_pEnd ? *p : '\0'; }

  const char *m_src, *m_srcEnd, *m_pat, *m_pEnd;
  std::uint64_t m_cap, m_cost = 0;
  bool m_stopped = false;
  int m_depth = kMaxDepth;
  int m_level = 0;
  Capture m_capture[kMaxCaptures];
};

/// True if the matcher has nothing to do for `pattern` beyond a plain
/// substring search (no special characters, as Lua's own test).
bool patternHasNoSpecials(std::string_view pattern);

}  // namespace tumble::script
