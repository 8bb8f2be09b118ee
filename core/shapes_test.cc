#include "core/shapes.h"

#include <gtest/gtest.h>

namespace markerbench {
namespace {

constexpr double kTol = 1e-12;

TEST(Shapes, BoxOutlineIsCounterClockwiseFromBottomLeft) {
  const Eigen::AlignedBox2d box(Eigen::Vector2d(-1.0, -2.0), Eigen::Vector2d(3.0, 4.0));
  const std::vector<Eigen::Vector2d> corners = BoxOutline(box, 1);
  ASSERT_EQ(corners.size(), 4u);
  EXPECT_EQ(corners[0], Eigen::Vector2d(-1.0, -2.0));
  EXPECT_EQ(corners[1], Eigen::Vector2d(3.0, -2.0));
  EXPECT_EQ(corners[2], Eigen::Vector2d(3.0, 4.0));
  EXPECT_EQ(corners[3], Eigen::Vector2d(-1.0, 4.0));
  const std::vector<Eigen::Vector2d> outline = BoxOutline(box, 2);
  ASSERT_EQ(outline.size(), 8u);
  EXPECT_EQ(outline[1], Eigen::Vector2d(1.0, -2.0));  // midpoint of the bottom side
}

TEST(Shapes, CrescentArcsPassThroughTheTipsWithTheirSagittas) {
  const Eigen::Vector2d tip0(0.03, 0.0), tip1(0.0, -0.03);
  const CrescentShape c = CrescentFromTips(tip0, tip1, 0.012, 0.005);
  for (const DiskShape& circle : {c.outer, c.inner}) {
    EXPECT_NEAR((tip0 - circle.center).norm(), circle.radius, kTol);
    EXPECT_NEAR((tip1 - circle.center).norm(), circle.radius, kTol);
  }
  // The arcs bulge to the left of tip0 → tip1, i.e. away from the origin here.
  const Eigen::Vector2d mid = 0.5 * (tip0 + tip1);
  const Eigen::Vector2d left = Eigen::Vector2d(1.0, -1.0).normalized();
  EXPECT_NEAR((mid + 0.012 * left - c.outer.center).norm(), c.outer.radius, kTol);
  EXPECT_NEAR((mid + 0.005 * left - c.inner.center).norm(), c.inner.radius, kTol);
}

}  // namespace
}  // namespace markerbench
