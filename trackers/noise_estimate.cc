#include "trackers/noise_estimate.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>

namespace markerbench {

double EstimateNoiseSigma(const cv::Mat& channel) {
  std::array<int, 256> histogram{};
  int count = 0;
  for (int y = 0; y < channel.rows; y += 2) {
    const uint8_t* row = channel.ptr<uint8_t>(y);
    for (int x = 1; x < channel.cols; ++x) {
      ++histogram[std::abs(row[x] - row[x - 1])];
      ++count;
    }
  }
  int seen = 0, median = 0;
  while (median < 255 && (seen += histogram[median]) < (count + 1) / 2) ++median;
  return 1.4826 * median / std::sqrt(2.0) / 255.0;
}

}  // namespace markerbench
