#include "trackers/bilinear_sample.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

namespace markerbench {
namespace {

// A 3x2 image: pixel (x, y) at index y * 3 + x, its centre at the integer point (x, y).
constexpr std::array<uint8_t, 6> kImage = {0, 30, 60, 90, 120, 150};

double At(double x, double y) { return BilinearSample(kImage.data(), 3, 2, {x, y}); }

TEST(BilinearSample, PixelCentresGiveThePixelsAndMidpointsAverageThem) {
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 3; ++x) EXPECT_NEAR(At(x, y), kImage[3 * y + x], 0.2) << x << "," << y;
  }
  EXPECT_DOUBLE_EQ(At(0.5, 0.0), 15.0);
  EXPECT_DOUBLE_EQ(At(0.0, 0.5), 45.0);
  EXPECT_DOUBLE_EQ(At(1.25, 0.5), 82.5);
}

TEST(BilinearSample, PointsOutsideAreClampedToTheBorder) {
  EXPECT_DOUBLE_EQ(At(-5.0, -5.0), 0.0);
  EXPECT_NEAR(At(10.0, 10.0), 150.0, 0.2);
}

// A point from a degenerate homography: NaN, never a read outside the image.
TEST(BilinearSample, ANanPointReadsNan) {
  const double nan = std::nan("");
  EXPECT_TRUE(std::isnan(At(nan, 0.5)));
  EXPECT_TRUE(std::isnan(At(0.5, nan)));
}

}  // namespace
}  // namespace markerbench
