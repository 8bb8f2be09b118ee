#include "trackers/byte_histogram.h"

namespace markerbench {

void ByteHistogram::Add(const uint8_t* values, int n) {
  int x = 0;
  for (; x + kLanes <= n; x += kLanes) {
    for (int lane = 0; lane < kLanes; ++lane) ++lanes_[lane][values[x + lane]];
  }
  for (; x < n; ++x) ++lanes_[0][values[x]];
  total_ += n;
}

std::array<int, 256> ByteHistogram::Counts() const {
  std::array<int, 256> counts{};
  for (const std::array<int, 256>& lane : lanes_) {
    for (int level = 0; level < 256; ++level) counts[level] += lane[level];
  }
  return counts;
}

int ByteHistogram::Median() const {
  const std::array<int, 256> counts = Counts();
  int seen = 0, median = 0;
  while (median < 255 && (seen += counts[median]) < (total_ + 1) / 2) ++median;
  return median;
}

}  // namespace markerbench
