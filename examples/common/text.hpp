#pragma once
// Number formatting of the examples' picture captions (their reports: report.hpp).

#include <iomanip>
#include <sstream>
#include <string>

namespace sylva_examples {

/// `v` with `digits` decimals (std::fixed).
inline std::string fixed(double v, int digits) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(digits) << v;
  return os.str();
}

}  // namespace sylva_examples
