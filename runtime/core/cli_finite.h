#pragma once
// A CLI11 check for number options: CLI11 reads "nan" and "inf" as numbers
// and its range checks let NaN through (every comparison with NaN is false),
// so every number option of the runtime and the tools also gets this.
// Header-only: only programs that already use CLI11 include it.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdlib>
#include <string>

namespace tumble {

inline const CLI::Validator kFinite(
    [](std::string& text) -> std::string {
      char* end = nullptr;
      const double v = std::strtod(text.c_str(), &end);
      if (end == text.c_str() || *end != '\0' || !std::isfinite(v)) return "expected a finite number, got " + text;
      return {};
    },
    "FINITE");

}  // namespace tumble
