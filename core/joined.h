// Lists of names in messages and headers: "a, b, c".
#pragma once

#include <string>
#include <vector>

namespace markerbench {

// `items` separated by `separator` (an empty item too); empty for no items.
inline std::string Joined(const std::vector<std::string>& items,
                          const std::string& separator = ", ") {
  std::string text;
  for (size_t i = 0; i < items.size(); ++i) text += (i == 0 ? "" : separator) + items[i];
  return text;
}

}  // namespace markerbench
