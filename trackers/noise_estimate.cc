#include "trackers/noise_estimate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <vector>

namespace markerbench {

double EstimateNoiseSigma(const cv::Mat& channel) {
  // A row's differences first (a loop the compiler vectorises), then counted in two
  // histograms in turn, summed at the end: neighbouring differences mostly fall in the same
  // few bins, and one histogram's increments would wait on each other (a third less time).
  std::array<int, 256> even{}, odd{};
  std::vector<uint8_t> differences(static_cast<size_t>(std::max(0, channel.cols - 1)));
  const int n = static_cast<int>(differences.size());
  int count = 0;
  for (int y = 0; y < channel.rows; y += 2) {
    const uint8_t* row = channel.ptr<uint8_t>(y);
    for (int x = 0; x < n; ++x) {
      differences[x] = static_cast<uint8_t>(std::abs(row[x + 1] - row[x]));
    }
    int x = 0;
    for (; x + 1 < n; x += 2) {
      ++even[differences[x]];
      ++odd[differences[x + 1]];
    }
    if (x < n) ++even[differences[x]];
    count += n;
  }
  int seen = 0, median = 0;
  while (median < 255 && (seen += even[median] + odd[median]) < (count + 1) / 2) ++median;
  return 1.4826 * median / std::sqrt(2.0) / 255.0;
}

}  // namespace markerbench
