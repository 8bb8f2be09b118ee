// The upper median of a sample (the element of rank n / 2, counting from 0: for an even n
// the larger of the middle two), by partial sorting. The trackers' robust levels and scales
// use it; `values` must not be empty.
#pragma once

#include <algorithm>
#include <vector>

namespace markerbench {

template <typename T>
T UpperMedian(std::vector<T> values) {
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

}  // namespace markerbench
