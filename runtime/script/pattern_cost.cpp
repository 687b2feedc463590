#include "script/internal/pattern_cost.h"

#include <cctype>
#include <cstring>

namespace tumble::script {

namespace {

constexpr char kEsc = '%';

bool matchClass(int c, int cl) {
  bool res;
  switch (std::tolower(cl)) {
    case 'a': res = std::isalpha(c); break;
    case 'c': res = std::iscntrl(c); break;
    case 'd': res = std::isdigit(c); break;
    case 'g': res = std::isgraph(c); break;
    case 'l': res = std::islower(c); break;
    case 'p': res = std::ispunct(c); break;
    case 's': res = std::isspace(c); break;
    case 'u': res = std::isupper(c); break;
    case 'w': res = std::isalnum(c); break;
    case 'x': res = std::isxdigit(c); break;
    case 'z': res = c == 0; break;  // deprecated in Lua 5.2, still matched by 5.4
    default: return cl == c;
  }
  return std::isupper(cl) ? !res : res;
}

// A set "[...]" from p (at '[') to ec (at its ']').
bool matchSet(int c, const char* p, const char* ec) {
  bool found = true;
  if (*(p + 1) == '^') {
    found = false;
    ++p;
  }
  while (++p < ec) {
    if (*p == kEsc) {
      ++p;
      if (matchClass(c, static_cast<unsigned char>(*p))) return found;
    } else if (*(p + 1) == '-' && p + 2 < ec) {
      p += 2;
      if (static_cast<unsigned char>(*(p - 2)) <= c && c <= static_cast<unsigned char>(*p)) return found;
    } else if (static_cast<unsigned char>(*p) == c) {
      return found;
    }
  }
  return !found;
}

}  // namespace

bool patternHasNoSpecials(std::string_view pattern) {
  for (char c : pattern)
    if (std::strchr("^$*+?.([%-", c) && c != '\0') return false;
  return true;
}

PatternCost::PatternCost(std::string_view subject, std::string_view pattern, std::uint64_t cap)
    : m_src(subject.data()),
      m_srcEnd(subject.data() + subject.size()),
      m_pat(pattern.data()),
      m_pEnd(pattern.data() + pattern.size()),
      m_cap(cap) {}

void PatternCost::add(std::uint64_t units) {
  m_cost += units;
  if (m_cost > m_cap) m_stopped = true;
}

bool PatternCost::step() {
  if (m_stopped) return false;
  if (++m_cost > m_cap) m_stopped = true;
  return !m_stopped;
}

long long PatternCost::matchAt(std::size_t at, std::size_t patternStart) {
  m_level = 0;
  m_depth = kMaxDepth;
  const char* e = match(m_src + at, m_pat + patternStart);
  return e && !m_stopped ? e - m_src : -1;
}

const char* PatternCost::classEnd(const char* p) {
  // Lua strings end in '\0', so Lua's matcher may read one past the end; at() does the same.
  if (*p++ == kEsc) {
    if (p >= m_pEnd) return stop(), nullptr;  // "malformed pattern (ends with '%')"
    return p + 1;
  }
  if (*(p - 1) == '[') {
    if (at(p) == '^') ++p;
    do {
      if (p >= m_pEnd) return stop(), nullptr;  // "malformed pattern (missing ']')"
      if (*(p++) == kEsc && p < m_pEnd) ++p;
    } while (at(p) != ']');
    return p + 1;
  }
  return p;
}

bool PatternCost::singleMatch(const char* s, const char* p, const char* ep) {
  if (!step() || s >= m_srcEnd) return false;
  const int c = static_cast<unsigned char>(*s);
  switch (*p) {
    case '.': return true;
    case kEsc: return matchClass(c, static_cast<unsigned char>(*(p + 1)));
    case '[': return matchSet(c, p, ep - 1);
    default: return static_cast<unsigned char>(*p) == c;
  }
}

const char* PatternCost::matchBalance(const char* s, const char* p) {
  if (p >= m_pEnd - 1) return stop(), nullptr;  // "missing arguments to '%b'"
  if (s >= m_srcEnd || *s != *p) return nullptr;
  const char open = *p, close = *(p + 1);
  int depth = 1;
  while (++s < m_srcEnd) {
    if (!step()) return nullptr;
    if (*s == close) {
      if (--depth == 0) return s + 1;
    } else if (*s == open) {
      ++depth;
    }
  }
  return nullptr;
}

const char* PatternCost::matchBackReference(const char* s, int digit) {
  const int l = digit - '1';
  if (l < 0 || l >= m_level || m_capture[l].len == kUnfinished) return stop(), nullptr;  // "invalid capture index"
  const long long len = m_capture[l].len;
  if (len < 0) return nullptr;  // a position capture never matches text
  add(std::uint64_t(len) + 1);
  if (m_stopped) return nullptr;
  if (m_srcEnd - s >= len && std::memcmp(m_src + m_capture[l].init, s, std::size_t(len)) == 0) return s + len;
  return nullptr;
}

const char* PatternCost::startCapture(const char* s, const char* p, long long what) {
  if (m_level >= kMaxCaptures) return stop(), nullptr;  // "too many captures"
  m_capture[m_level].init = std::size_t(s - m_src);
  m_capture[m_level].len = what;
  ++m_level;
  const char* res = match(s, p);
  if (!res) --m_level;
  return res;
}

const char* PatternCost::endCapture(const char* s, const char* p) {
  int l = -1;
  for (int k = m_level - 1; k >= 0; --k)
    if (m_capture[k].len == kUnfinished) {
      l = k;
      break;
    }
  if (l < 0) return stop(), nullptr;  // "invalid pattern capture"
  m_capture[l].len = (s - m_src) - (long long)m_capture[l].init;
  const char* res = match(s, p);
  if (!res) m_capture[l].len = kUnfinished;
  return res;
}

const char* PatternCost::maxExpand(const char* s, const char* p, const char* ep) {
  std::ptrdiff_t i = 0;
  while (singleMatch(s + i, p, ep)) ++i;
  for (; i >= 0 && !m_stopped; --i)
    if (const char* res = match(s + i, ep + 1)) return res;
  return nullptr;
}

const char* PatternCost::minExpand(const char* s, const char* p, const char* ep) {
  for (;;) {
    if (const char* res = match(s, ep + 1)) return res;
    if (m_stopped || !singleMatch(s, p, ep)) return nullptr;
    ++s;
  }
}

const char* PatternCost::match(const char* s, const char* p) {
  if (m_stopped) return nullptr;
  if (m_depth-- == 0) {  // "pattern too complex"
    stop();
    return nullptr;
  }
  for (;;) {
    if (!step()) {
      s = nullptr;
      break;
    }
    if (p == m_pEnd) break;
    bool plain = false;
    switch (*p) {
      case '(':
        s = at(p + 1) == ')' ? startCapture(s, p + 2, kPosition) : startCapture(s, p + 1, kUnfinished);
        break;
      case ')':
        s = endCapture(s, p + 1);
        break;
      case '$':
        if (p + 1 != m_pEnd) {
          plain = true;
          break;
        }
        s = s == m_srcEnd ? s : nullptr;
        break;
      case kEsc:
        switch (at(p + 1)) {
          case 'b':
            s = matchBalance(s, p + 2);
            if (s) {
              p += 4;
              continue;
            }
            break;
          case 'f': {
            p += 2;
            if (at(p) != '[') {  // "missing '[' after '%f' in pattern"
              stop();
              s = nullptr;
              break;
            }
            const char* ep = classEnd(p);
            if (!ep) {
              s = nullptr;
              break;
            }
            const int prev = s == m_src ? 0 : static_cast<unsigned char>(*(s - 1));
            const int cur = s < m_srcEnd ? static_cast<unsigned char>(*s) : 0;
            if (!matchSet(prev, p, ep - 1) && matchSet(cur, p, ep - 1)) {
              p = ep;
              continue;
            }
            s = nullptr;
            break;
          }
          case '0': case '1': case '2': case '3': case '4':
          case '5': case '6': case '7': case '8': case '9':
            s = matchBackReference(s, static_cast<unsigned char>(*(p + 1)));
            if (s) {
              p += 2;
              continue;
            }
            break;
          default: plain = true; break;
        }
        break;
      default: plain = true; break;
    }
    if (!plain) break;
    // A single-character item, possibly followed by a quantifier.
    const char* ep = classEnd(p);
    if (!ep) {
      s = nullptr;
      break;
    }
    const char q = at(ep);
    if (!singleMatch(s, p, ep)) {
      if (m_stopped) {
        s = nullptr;
        break;
      }
      if (q == '*' || q == '?' || q == '-') {  // zero repetitions are fine
        p = ep + 1;
        continue;
      }
      s = nullptr;
      break;
    }
    if (q == '?') {
      if (const char* res = match(s + 1, ep + 1)) {
        s = res;
        break;
      }
      if (m_stopped) {
        s = nullptr;
        break;
      }
      p = ep + 1;
      continue;
    }
    if (q == '+') {
      s = maxExpand(s + 1, p, ep);
      break;
    }
    if (q == '*') {
      s = maxExpand(s, p, ep);
      break;
    }
    if (q == '-') {
      s = minExpand(s, p, ep);
      break;
    }
    ++s;
    p = ep;
  }
  ++m_depth;
  return m_stopped ? nullptr : s;
}

}  // namespace tumble::script
