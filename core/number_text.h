// Numbers as text. For CSV files and manifests: std::to_chars's shortest form that reads back
// to the same double, independent of locale and thread count.
#pragma once

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>

namespace markerbench {

inline std::string NumberText(double value) {
  char buffer[32];
  const std::to_chars_result result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
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
