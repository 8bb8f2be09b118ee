// Lists of names in messages and headers: "a, b, c".
#pragma once

#include <string>
#include <vector>

namespace markerbench {

// `items` separated by `separator`; empty for no items.
inline std::string Joined(const std::vector<std::string>& items,
                          const std::string& separator = ", ") {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : separator) + item;
  return text;
}

}  // namespace markerbench
