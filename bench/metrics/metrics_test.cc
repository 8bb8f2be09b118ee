#include "bench/metrics/metrics.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

namespace markerbench {
namespace {

constexpr double kTol = 1e-12;
constexpr double kDeg = M_PI / 180.0;

// Camera on the marker's z axis at `distance`, looking down at it (camera z = -marker z).
Rigid3 Overhead(double distance) {
  const Eigen::Matrix3d r = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
  return Rigid3(r, Eigen::Vector3d(0.0, 0.0, distance));
}

// `pose` with its rotation turned by `angle_deg` about the camera's x axis, camera centre kept.
Rigid3 Turned(const Rigid3& pose, double angle_deg) {
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(angle_deg * kDeg, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Eigen::Vector3d center = CameraCenterInMarker(pose);
  const Eigen::Matrix3d r = turn * pose.rotation;
  return Rigid3(r, -r * center);
}

TEST(Metrics, PoseErrorsOfHandMadeHypotheses) {
  const Rigid3 truth = Overhead(1.0);
  // Camera centre moved 3 cm along x and 4 cm along z in the marker frame: 5 cm off.
  Rigid3 moved = truth;
  moved.translation = -truth.rotation * Eigen::Vector3d(0.03, 0.0, 1.04);
  const Rigid3 turned = Turned(truth, 40.0);  // right centre, 40° off
  const PoseErrors e = ComputePoseErrors({turned, moved}, truth);
  EXPECT_NEAR(e.position_error_m, 0.0, kTol);
  EXPECT_NEAR(e.rotation_error_deg, 40.0, 1e-9);
  // The oracle takes the hypothesis with the least rotation error: `moved` (0°).
  EXPECT_NEAR(e.best_position_error_m, 0.05, kTol);
  EXPECT_NEAR(e.best_rotation_error_deg, 0.0, 1e-6);
  EXPECT_TRUE(e.flip);  // first 40° off (> 30°), second within 5°
}

TEST(Metrics, NoHypothesisGivesNaNAndNoFlip) {
  const PoseErrors e = ComputePoseErrors({}, Overhead(1.0));
  EXPECT_TRUE(std::isnan(e.position_error_m));
  EXPECT_TRUE(std::isnan(e.best_rotation_error_deg));
  EXPECT_FALSE(e.flip);
  EXPECT_EQ(BestHypothesisIndex({}, Overhead(1.0)), -1);
}

TEST(Metrics, FlipNeedsAWrongFirstAndARightOther) {
  const Rigid3 truth = Overhead(0.6);
  EXPECT_FALSE(IsFlip({Turned(truth, 29.0), truth}, truth));               // first not wrong enough
  EXPECT_FALSE(IsFlip({Turned(truth, 45.0), Turned(truth, 6.0)}, truth));  // other not right
  EXPECT_TRUE(IsFlip({Turned(truth, 45.0), Turned(truth, 4.0)}, truth));
  EXPECT_FALSE(IsFlip({Turned(truth, 45.0)}, truth));  // only one hypothesis
  EXPECT_EQ(BestHypothesisIndex({Turned(truth, 45.0), Turned(truth, 4.0)}, truth), 1);
}

TEST(Metrics, SuccessIsTenPercentOfTheDistance) {
  EXPECT_TRUE(IsSuccess(true, 0.1, 1.0, 0.1));
  EXPECT_FALSE(IsSuccess(true, 0.1001, 1.0, 0.1));
  EXPECT_FALSE(IsSuccess(false, 0.0, 1.0, 0.1));
  EXPECT_FALSE(IsSuccess(true, NAN, 1.0, 0.1));
}

TEST(Metrics, OrderStatisticsSkipNaNAndInterpolate) {
  EXPECT_EQ(Median({3.0, 1.0, 2.0}), 2.0);
  EXPECT_EQ(Median({4.0, 1.0, NAN, 2.0, 3.0}), 2.5);
  EXPECT_EQ(Mean({1.0, NAN, 2.0, 6.0}), 3.0);
  // numpy.percentile([1, 2, 3, 4, 5, 6, 7, 8, 9, 10], 90) = 9.1
  EXPECT_NEAR(Percentile({10, 9, 8, 7, 6, 5, 4, 3, 2, 1}, 90.0), 9.1, kTol);
  EXPECT_EQ(Percentile({5.0}, 90.0), 5.0);
  EXPECT_TRUE(std::isnan(Median({NAN})));
  // +inf is a value (an unobservable frame's bound), larger than every other.
  EXPECT_EQ(Median({INFINITY, 1.0, 2.0}), 2.0);
  EXPECT_EQ(Median({INFINITY, 1.0, INFINITY}), INFINITY);
  EXPECT_EQ(Median({INFINITY, 1.0}), INFINITY);
  EXPECT_TRUE(std::isnan(Mean({})));
}

}  // namespace
}  // namespace markerbench
