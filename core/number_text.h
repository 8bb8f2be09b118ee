// Numbers as text. For CSV files and manifests: std::to_chars's shortest form that reads back
// to the same double, independent of locale and thread count.
#pragma once

#include <charconv>
#include <cmath>
#include <cstdint>
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

inline std::string BoolText(bool value) { return value ? "true" : "false"; }

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

// `text` read whole as a whole number in [lo, hi] ("12" and "12.0" alike); nullopt otherwise,
// never an out-of-range cast. For counts and frame numbers (|values| < 2^53).
inline std::optional<long long> ParseWholeNumber(const std::string& text, double lo, double hi) {
  const std::optional<double> value = ParseFiniteNumber(text);
  if (!value || !(*value >= lo && *value <= hi) || *value != std::floor(*value)) {
    return std::nullopt;
  }
  return static_cast<long long>(*value);
}

// `text` read whole as a decimal unsigned 64-bit number (a seed: every bit kept); nullopt
// for a sign, a fraction, an exponent or an overflow.
inline std::optional<uint64_t> ParseUnsigned64(const std::string& text) {
  uint64_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size()) {
    return std::nullopt;
  }
  return value;
}

}  // namespace markerbench
