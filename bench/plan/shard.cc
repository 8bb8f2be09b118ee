#include "bench/plan/shard.h"

#include <charconv>
#include <optional>
#include <string_view>

#include "core/config_error.h"

namespace markerbench {
namespace {

// A whole decimal number filling `text`.
std::optional<int> ParseCount(std::string_view text) {
  int value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

}  // namespace

Shard ParseShard(const std::string& text, const std::string& option) {
  const size_t slash = text.find('/');
  const std::optional<int> index = slash == std::string::npos
                                       ? std::nullopt
                                       : ParseCount(std::string_view(text).substr(0, slash));
  const std::optional<int> count = slash == std::string::npos
                                       ? std::nullopt
                                       : ParseCount(std::string_view(text).substr(slash + 1));
  if (!index || !count || *count < 1 || *index < 0 || *index >= *count) {
    throw ConfigError(option + ": expected I/N with 0 <= I < N (shard I of N), got '" + text + "'");
  }
  return {*index, *count};
}

bool InShard(const PlannedFrame& frame, int trials, const Shard& shard) {
  const long long group = static_cast<long long>(frame.cell) * trials + frame.trial;
  return group % shard.count == shard.index;
}

}  // namespace markerbench
