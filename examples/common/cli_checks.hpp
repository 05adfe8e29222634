#pragma once
// CLI11 validators shared by the example programs: a number that must be finite, and
// optionally > 0 or >= 0, refused with a plain sentence (CLI11's own PositiveNumber prints
// the whole double range on failure).

#include <cmath>
#include <sstream>
#include <string>

#include <CLI/CLI.hpp>

namespace sylva_examples {

/// A finite number; with `positive_only`, also > 0 (>= 0 with `allow_zero`).
inline CLI::Validator finite(bool positive_only, bool allow_zero = false) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        std::istringstream is(text);
        double value = 0.0;
        if (!(is >> value) || !std::isfinite(value)) return "must be a finite number, got " + text;
        if (positive_only && (value < 0.0 || (!allow_zero && value == 0.0)))
          return std::string("must be ") + (allow_zero ? ">= 0" : "> 0") + ", got " + text;
        return std::string();
      },
      positive_only ? (allow_zero ? "NONNEGATIVE" : "POSITIVE") : "NUMBER");
}

/// A finite number > 0 (>= 0 with `allow_zero`).
inline CLI::Validator positive(bool allow_zero) { return finite(true, allow_zero); }

}  // namespace sylva_examples
