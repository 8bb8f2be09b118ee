#include "trackers/noise_estimate.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "trackers/byte_histogram.h"

namespace markerbench {
namespace {

// The rows whose differences the estimate takes, and those its first guess takes.
constexpr int kRowStep = 2;
constexpr int kGuessRowStep = 16;

// |a - b| in bytes (which the compiler vectorises 16 at a time).
inline uint8_t AbsoluteDifference(uint8_t a, uint8_t b) { return a > b ? a - b : b - a; }

// |row[x + 1] - row[x]| for x < differences.size().
void RowDifferences(const uint8_t* row, std::vector<uint8_t>* differences) {
  const int n = static_cast<int>(differences->size());
  uint8_t* out = differences->data();
  for (int x = 0; x < n; ++x) out[x] = AbsoluteDifference(row[x], row[x + 1]);
}

// The histogram of the differences on every `row_step`-th row.
ByteHistogram HistogramOfRows(const cv::Mat& channel,
                              int row_step,
                              std::vector<uint8_t>* differences) {
  ByteHistogram histogram;
  for (int y = 0; y < channel.rows; y += row_step) {
    RowDifferences(channel.ptr<uint8_t>(y), differences);
    histogram.Add(differences->data(), static_cast<int>(differences->size()));
  }
  return histogram;
}

// How many differences on every kRowStep-th row lie below `level` and how many at most at it.
struct CountsAround {
  int below = 0, at_most = 0, total = 0;
};
CountsAround CountAround(const cv::Mat& channel, uint8_t level) {
  const int n = std::max(0, channel.cols - 1);
  CountsAround out;
  for (int y = 0; y < channel.rows; y += kRowStep) {
    const uint8_t* row = channel.ptr<uint8_t>(y);
    // Counted in bytes too, at most 255 differences at a time: 240, 15 vectors of 16.
    constexpr int kChunk = 240;
    for (int start = 0; start < n; start += kChunk) {
      const int end = std::min(n, start + kChunk);
      uint8_t below = 0, at_most = 0;
      for (int x = start; x < end; ++x) {
        const uint8_t difference = AbsoluteDifference(row[x], row[x + 1]);
        below += difference < level;
        at_most += difference <= level;
      }
      out.below += below;
      out.at_most += at_most;
    }
    out.total += n;
  }
  return out;
}

}  // namespace

double EstimateNoiseSigma(const cv::Mat& channel) {
  std::vector<uint8_t> differences(static_cast<size_t>(std::max(0, channel.cols - 1)));
  // The median guessed from a few of the rows, then checked on all of them by counting the
  // differences below it and at it, vectorised: a histogram's increments are not (with them,
  // the estimate took 4-5 % of the circle tracker's time). Where the guess is not the median,
  // the histogram of all the rows gives it.
  const int guess = HistogramOfRows(channel, kGuessRowStep, &differences).Median();
  const CountsAround counts = CountAround(channel, static_cast<uint8_t>(guess));
  const int half = (counts.total + 1) / 2;
  const int median = counts.below < half && counts.at_most >= half
                         ? guess
                         : HistogramOfRows(channel, kRowStep, &differences).Median();
  return 1.4826 * median / std::sqrt(2.0) / 255.0;
}

}  // namespace markerbench
