// Numbers as text for CSV files and manifests: the shortest "%.{15,16,17}g" form that reads
// back to the same double, independent of locale and thread count.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>

namespace markerbench {

inline std::string NumberText(double value) {
  char buffer[32];
  for (int digits = 15; digits < 17; ++digits) {
    std::snprintf(buffer, sizeof(buffer), "%.*g", digits, value);
    if (std::strtod(buffer, nullptr) == value) return buffer;
  }
  std::snprintf(buffer, sizeof(buffer), "%.17g", value);
  return buffer;
}

}  // namespace markerbench
