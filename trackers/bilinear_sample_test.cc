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

// One channel of an interleaved image reads as that channel alone would: the grey image above
// as channel 1 of three, the other channels far off.
TEST(BilinearSample, AChannelOfAnInterleavedImageReadsAsAGreyImage) {
  std::array<uint8_t, 18> interleaved{};
  for (size_t i = 0; i < kImage.size(); ++i) {
    interleaved[3 * i] = 255;
    interleaved[3 * i + 1] = kImage[i];
    interleaved[3 * i + 2] = static_cast<uint8_t>(200 - kImage[i]);
  }
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(0.5, 0.0),
                                   Eigen::Vector2d(1.25, 0.5),
                                   Eigen::Vector2d(1.9, 0.7),
                                   Eigen::Vector2d(-3.0, 9.0)}) {
    EXPECT_DOUBLE_EQ(BilinearSample(interleaved.data(), 3, 2, 3, 1, p), At(p.x(), p.y()));
    EXPECT_DOUBLE_EQ(BilinearSample(interleaved.data(), 3, 2, 3, 2, p), 200.0 - At(p.x(), p.y()));
  }
}

// A point from a degenerate homography: NaN, never a read outside the image.
TEST(BilinearSample, ANanPointReadsNan) {
  const double nan = std::nan("");
  EXPECT_TRUE(std::isnan(At(nan, 0.5)));
  EXPECT_TRUE(std::isnan(At(0.5, nan)));
}

}  // namespace
}  // namespace markerbench
