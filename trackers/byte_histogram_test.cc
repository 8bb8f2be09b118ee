#include "trackers/byte_histogram.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/random.h"

namespace markerbench {
namespace {

// Runs of equal values (as on paper), of lengths 1-9, at random levels.
std::vector<uint8_t> RunsOfLevels(int n, uint64_t seed) {
  Rng rng(seed);
  std::vector<uint8_t> values;
  while (static_cast<int>(values.size()) < n) {
    const auto level = static_cast<uint8_t>(rng.Uniform(0.0, 256.0));
    const int run = 1 + static_cast<int>(rng.Uniform(0.0, 9.0));
    for (int k = 0; k < run && static_cast<int>(values.size()) < n; ++k) values.push_back(level);
  }
  return values;
}

TEST(ByteHistogram, CountsEveryValueOnceAcrossCallsOfAnyLength) {
  // Lengths that leave 0-3 values after the lanes' groups of four.
  const std::vector<uint8_t> values = RunsOfLevels(1000, 7);
  std::array<int, 256> expected{};
  for (const uint8_t v : values) ++expected[v];
  ByteHistogram histogram;
  int start = 0;
  for (const int length : {0, 1, 2, 3, 4, 5, 6, 7, 333, 589, 50}) {
    histogram.Add(values.data() + start, length);
    start += length;
  }
  ASSERT_EQ(start, 1000);
  EXPECT_EQ(histogram.Counts(), expected);
  EXPECT_EQ(histogram.total(), 1000);
}

TEST(ByteHistogram, MedianIsTheLowerMiddleValue) {
  for (const int n : {1, 2, 5, 6, 999, 1000}) {
    SCOPED_TRACE("n " + std::to_string(n));
    std::vector<uint8_t> values = RunsOfLevels(n, 11 + n);
    ByteHistogram histogram;
    histogram.Add(values.data(), n);
    std::sort(values.begin(), values.end());
    EXPECT_EQ(histogram.Median(), values[(n - 1) / 2]);
  }
  EXPECT_EQ(ByteHistogram().Median(), 0);
}

}  // namespace
}  // namespace markerbench
