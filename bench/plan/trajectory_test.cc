#include "bench/plan/trajectory.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/marker_yaml.h"

namespace markerbench {
namespace {

constexpr double kGeometryTol = 1e-9;

TrialTrajectory StartAt(double distance_m, double tilt_deg, double azimuth_deg) {
  TrialTrajectory trial;
  trial.start.distance_m = distance_m;
  trial.start.tilt = tilt_deg * M_PI / 180.0;
  trial.start.azimuth = azimuth_deg * M_PI / 180.0;
  return trial;
}

TEST(Trajectory, OrbitTurnsTheAzimuthAtItsRateAndKeepsDistanceAndTilt) {
  TrajectoryOptions o;
  o.kind = TrajectoryKind::kOrbit;
  o.degrees_per_s = 45.0;
  o.static_s = 1.0;
  const Camera camera;
  const TrialTrajectory trial = StartAt(0.8, 30.0, 10.0);
  for (const double t : {0.0, 0.5, 1.0, 2.0, 3.0}) {
    const Eigen::Vector3d c = CameraCenterInMarker(TrajectoryPose(o, trial, camera, t));
    EXPECT_NEAR(c.norm(), 0.8, kGeometryTol);
    EXPECT_NEAR(std::acos(c.z() / c.norm()) * 180.0 / M_PI, 30.0, 1e-7);
    const double azimuth = std::atan2(c.y(), c.x()) * 180.0 / M_PI;
    EXPECT_NEAR(azimuth, 10.0 + 45.0 * std::max(0.0, t - 1.0), 1e-7) << "t = " << t;
  }
}

TEST(Trajectory, ApproachGoesLinearlyFromFarToNear) {
  TrajectoryOptions o;
  o.kind = TrajectoryKind::kApproach;
  o.duration_s = 4.0;
  o.to_m = 0.4;
  const Camera camera;
  const TrialTrajectory trial = StartAt(2.0, 20.0, 0.0);  // poses.distance_m
  const auto distance = [&](double t) {
    return CameraCenterInMarker(TrajectoryPose(o, trial, camera, t)).norm();
  };
  EXPECT_NEAR(distance(0.0), 2.0, kGeometryTol);
  EXPECT_NEAR(distance(2.0), 1.2, kGeometryTol);
  EXPECT_NEAR(distance(4.0), 0.4, kGeometryTol);
}

// The shake's speeds, measured by finite differences over a long run, are the ones asked
// for; it holds still during the static segment and is the same for the same seed.
TEST(Trajectory, HandheldShakeHasTheRmsSpeedsAskedFor) {
  TrajectoryOptions o;
  o.kind = TrajectoryKind::kHandheld;
  o.static_s = 0.5;
  o.linear_speed_m_s = 0.12;
  o.angular_speed_deg_s = 25.0;
  const Camera camera;
  Rng rng(7);
  TrialTrajectory trial = StartAt(0.6, 20.0, 40.0);
  trial.shake = Shake::Draw(o.linear_speed_m_s, o.angular_speed_deg_s, &rng);
  const Rigid3 at_rest = TrajectoryPose(o, trial, camera, 0.0);
  const Rigid3 still = TrajectoryPose(o, trial, camera, 0.5);
  EXPECT_LT((at_rest.translation - still.translation).norm(), kGeometryTol);
  constexpr double kStep = 1e-3, kSpan = 400.0;
  double linear_sq = 0.0, angular_sq = 0.0;
  int n = 0;
  for (double t = 0.5; t < 0.5 + kSpan; t += 0.05, ++n) {
    const Rigid3 a = TrajectoryPose(o, trial, camera, t);
    const Rigid3 b = TrajectoryPose(o, trial, camera, t + kStep);
    linear_sq +=
        (CameraCenterInMarker(b) - CameraCenterInMarker(a)).squaredNorm() / (kStep * kStep);
    const Eigen::AngleAxisd turn(b.rotation * a.rotation.transpose());
    angular_sq += std::pow(turn.angle() / kStep, 2);
  }
  EXPECT_NEAR(std::sqrt(linear_sq / n), 0.12, 0.012);
  EXPECT_NEAR(std::sqrt(angular_sq / n) * 180.0 / M_PI, 25.0, 2.5);
  Rng again(7);
  const Shake same = Shake::Draw(o.linear_speed_m_s, o.angular_speed_deg_s, &again);
  EXPECT_EQ(same.At(3.7), trial.shake.At(3.7));
}

TEST(Trajectory, FramesTimesAndOcclusions) {
  TrajectoryOptions o;
  o.fps = 30.0;
  o.duration_s = 2.0;
  o.exposure_s = 0.01;
  o.occlusions = {{10, 14}, {40, 40}};
  EXPECT_EQ(o.Frames(), 60);
  EXPECT_DOUBLE_EQ(o.FrameTime(15), 0.5);
  EXPECT_DOUBLE_EQ(o.TruthTime(15), 0.505);
  EXPECT_FALSE(o.Occluded(9));
  EXPECT_TRUE(o.Occluded(10));
  EXPECT_TRUE(o.Occluded(14));
  EXPECT_FALSE(o.Occluded(15));
  EXPECT_TRUE(o.Occluded(40));
}

TEST(Trajectory, SampledTrialsKeepTheMarkerInViewAtEveryFrame) {
  TrajectoryOptions o;
  o.kind = TrajectoryKind::kHandheld;
  o.duration_s = 3.0;
  o.exposure_s = 0.02;
  o.linear_speed_m_s = 0.2;
  o.angular_speed_deg_s = 40.0;
  const Camera camera;
  const std::vector<MarkerSpec> markers = {LoadMarkerYaml("scenarios/markers/circles_a.yaml")};
  PoseSamplerOptions poses;
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    const TrialTrajectory trial =
        SampleTrialTrajectory(o, poses, camera, markers, seed, seed + 100);
    for (int k = 0; k < o.Frames(); ++k) {
      const Rigid3 pose = TrajectoryPose(o, trial, camera, o.FrameTime(k));
      EXPECT_TRUE(
          MarkerFitsInImage(markers[0], camera, CamFromMarker(pose, markers[0]), poses.border_px));
    }
  }
  o.linear_speed_m_s = 100.0;  // leaves the view whatever the start
  EXPECT_THROW(SampleTrialTrajectory(o, poses, camera, markers, 1, 2), std::runtime_error);
}

}  // namespace
}  // namespace markerbench
