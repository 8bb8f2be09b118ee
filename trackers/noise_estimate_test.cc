#include "trackers/noise_estimate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "core/random.h"

namespace markerbench {
namespace {

// A grey image of `level` plus Gaussian noise of σ (0-255 units), rounded and clipped.
cv::Mat NoisyFlat(int rows, int cols, double level, double sigma, uint64_t seed) {
  Rng rng(seed);
  cv::Mat image(rows, cols, CV_8UC1);
  for (int y = 0; y < rows; ++y) {
    for (int x = 0; x < cols; ++x) {
      image.at<uint8_t>(y, x) =
          static_cast<uint8_t>(std::clamp(std::lround(level + sigma * rng.Gaussian()), 0L, 255L));
    }
  }
  return image;
}

// The estimate's definition, written plainly: the median of the absolute differences of
// horizontal neighbours on every other row (the lower one of an even count), as σ.
double ByDefinition(const cv::Mat& image) {
  std::vector<int> differences;
  for (int y = 0; y < image.rows; y += 2) {
    for (int x = 1; x < image.cols; ++x) {
      differences.push_back(std::abs(image.at<uint8_t>(y, x) - image.at<uint8_t>(y, x - 1)));
    }
  }
  std::sort(differences.begin(), differences.end());
  const int median = differences[(differences.size() - 1) / 2];
  return 1.4826 * median / std::sqrt(2.0) / 255.0;
}

TEST(EstimateNoiseSigma, IsTheMedianAbsoluteDifferenceOfNeighbours) {
  for (const double sigma : {0.0, 2.0, 7.0, 30.0}) {
    for (const int cols : {2, 5, 64, 333}) {
      const cv::Mat image = NoisyFlat(9, cols, 128.0, sigma, 17 + cols);
      EXPECT_EQ(EstimateNoiseSigma(image), ByDefinition(image)) << sigma << " " << cols;
    }
  }
}

TEST(EstimateNoiseSigma, IsTheMedianWhereAFewRowsMisleadItsGuess) {
  // Its guess comes from every 16th row: rows 0, 16, 32, ... flat (their differences 0, or
  // all large), the others noisy, so the guess is not the median and the histogram of all
  // the rows must give it.
  for (const int odd_level : {0, 200}) {
    cv::Mat image = NoisyFlat(64, 101, 128.0, 7.0, 23);
    for (int y = 0; y < image.rows; y += 16) {
      for (int x = 0; x < image.cols; ++x) image.at<uint8_t>(y, x) = x % 2 ? odd_level : 0;
    }
    EXPECT_EQ(EstimateNoiseSigma(image), ByDefinition(image)) << odd_level;
    EXPECT_GT(EstimateNoiseSigma(image), 0.0) << odd_level;
  }
}

TEST(EstimateNoiseSigma, FindsTheNoiseOfAFlatImage) {
  // The median of |n₁ - n₂| is 0.6745 √2 σ: within 10 % at these σ after 8-bit rounding.
  for (const double sigma : {10.0, 20.0, 40.0}) {
    const double found = 255.0 * EstimateNoiseSigma(NoisyFlat(200, 300, 128.0, sigma, 5));
    EXPECT_NEAR(found / sigma, 1.0, 0.1) << sigma;
  }
}

TEST(EstimateNoiseSigma, AnImageOfOneColumnHasNoDifferences) {
  EXPECT_EQ(EstimateNoiseSigma(NoisyFlat(4, 1, 128.0, 10.0, 3)), 0.0);
}

}  // namespace
}  // namespace markerbench
