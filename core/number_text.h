// Numbers as text for CSV files and manifests: shortest form that reads back to the same
// double ("%.17g"), independent of locale and thread count.
#pragma once

#include <cstdio>
#include <string>

namespace markerbench {

inline std::string NumberText(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.17g", value);
  return buffer;
}

}  // namespace markerbench
