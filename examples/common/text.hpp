#pragma once
// Number formatting shared by the example programs' text reports.

#include <iomanip>
#include <sstream>
#include <string>

namespace sylva_examples {

/// `v` with `digits` decimals (std::fixed), the way the reports print their figures.
inline std::string fixed(double v, int digits) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(digits) << v;
  return os.str();
}

}  // namespace sylva_examples
