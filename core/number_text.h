// Numbers as text. For CSV files and manifests: the shortest "%.{15,16,17}g" form that reads
// back to the same double, independent of locale and thread count.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
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

// An empty CSV field for NaN (no value), else NumberText.
inline std::string NumberTextOrEmpty(double value) {
  return std::isnan(value) ? std::string() : NumberText(value);
}

// `value` through a printf `format` for reports and tables; "-" for NaN (no value).
inline std::string FormattedOrDash(double value, const char* format) {
  if (std::isnan(value)) return "-";
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), format, value);
  return buffer;
}

// `text` read whole as a finite number (a trailing CR of a CRLF line aside): "0.6abc", "",
// "nan" and "1e999" are nullopt.
inline std::optional<double> ParseFiniteNumber(std::string text) {
  if (!text.empty() && text.back() == '\r') text.pop_back();
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (*end != '\0' || !std::isfinite(value)) return std::nullopt;
  return value;
}

}  // namespace markerbench
