#include "core/rigid3.h"

#include <gtest/gtest.h>

#include <cmath>

namespace markerbench {
namespace {

constexpr double kRoundTripTol = 1e-12;  // double precision, a handful of products

Rigid3 RandomRigid(int seed) {
  std::srand(seed);
  const Eigen::Quaterniond q = Eigen::Quaterniond::UnitRandom();
  return {q.toRotationMatrix(), Eigen::Vector3d::Random()};
}

TEST(Rigid3, IsRotation) {
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
  EXPECT_TRUE(IsRotation(r));
  EXPECT_FALSE(IsRotation(-r)) << "a reflection";
  Eigen::Matrix3d off = r;
  off(0, 0) += 1e-5;
  EXPECT_FALSE(IsRotation(off));
  EXPECT_TRUE(IsRotation(off, 1e-4));
  off(1, 1) = NAN;
  EXPECT_FALSE(IsRotation(off, 1.0));
}

TEST(Rigid3, InverseComposesToIdentity) {
  for (int seed = 1; seed <= 20; ++seed) {
    const Rigid3 b_from_a = RandomRigid(seed);
    const Rigid3 a_from_a = b_from_a.Inverse() * b_from_a;
    EXPECT_LE((a_from_a.rotation - Eigen::Matrix3d::Identity()).norm(), kRoundTripTol);
    EXPECT_LE(a_from_a.translation.norm(), kRoundTripTol);
  }
}

TEST(Rigid3, CompositionMatchesSequentialApplication) {
  const Rigid3 b_from_a = RandomRigid(3);
  const Rigid3 c_from_b = RandomRigid(4);
  const Eigen::Vector3d x_a(0.3, -1.2, 2.0);
  const Eigen::Vector3d direct = (c_from_b * b_from_a) * x_a;
  const Eigen::Vector3d sequential = c_from_b * (b_from_a * x_a);
  EXPECT_LE((direct - sequential).norm(), kRoundTripTol);
  EXPECT_LE((b_from_a.Inverse() * (b_from_a * x_a) - x_a).norm(), kRoundTripTol);
}

TEST(Rigid3, CameraCenterMapsToCameraOrigin) {
  const Rigid3 cam_from_marker = RandomRigid(7);
  const Eigen::Vector3d center = CameraCenterInMarker(cam_from_marker);
  EXPECT_LE((cam_from_marker * center).norm(), kRoundTripTol);
}

TEST(Rigid3, RayFromPlaneMapsPlanePointsAndBack) {
  const Rigid3 cam_from_marker = RandomRigid(8);
  const Eigen::Matrix3d H = RayFromPlane(cam_from_marker);
  for (const Eigen::Vector2d& xy : {Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(0.3, -1.2)}) {
    EXPECT_LE(
        (H * xy.homogeneous() - cam_from_marker * Eigen::Vector3d(xy.x(), xy.y(), 0.0)).norm(),
        kRoundTripTol);
    const Eigen::Vector3d ray = 3.0 * (H * xy.homogeneous());  // any point of the ray
    EXPECT_LE(((H.inverse() * ray).hnormalized() - xy).norm(), kRoundTripTol);
  }
}

TEST(Rigid3, RotationFromVectorRoundTrips) {
  for (int seed = 1; seed <= 20; ++seed) {
    const Eigen::Matrix3d r = RandomRigid(seed).rotation;
    const Eigen::AngleAxisd angle_axis(r);
    const Eigen::Matrix3d back = RotationFromVector(angle_axis.angle() * angle_axis.axis());
    EXPECT_LT((back - r).norm(), kRoundTripTol) << "seed " << seed;
  }
  // |v| is the angle about v, in either direction.
  const Eigen::Vector3d v(0.3, -0.4, 1.2);
  EXPECT_NEAR(RotationAngleBetween(RotationFromVector(v), Eigen::Matrix3d::Identity()),
              v.norm(),
              kRoundTripTol);
  EXPECT_LT((RotationFromVector(v) * v - v).norm(), kRoundTripTol);  // the axis stays
  EXPECT_LT((RotationFromVector(-v) * RotationFromVector(v) - Eigen::Matrix3d::Identity()).norm(),
            kRoundTripTol);
  EXPECT_EQ(RotationFromVector(Eigen::Vector3d::Zero()), Eigen::Matrix3d::Identity());
}

TEST(Rigid3, RotationAngleBetween) {
  const Eigen::Matrix3d a = RandomRigid(9).rotation;
  const Eigen::Matrix3d b =
      a * Eigen::AngleAxisd(0.25, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  EXPECT_NEAR(RotationAngleBetween(a, b), 0.25, 1e-12);
  EXPECT_NEAR(RotationAngleBetween(a, a), 0.0, 1e-7);
}

}  // namespace
}  // namespace markerbench
