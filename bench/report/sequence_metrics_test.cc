#include "bench/report/sequence_metrics.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

namespace markerbench {
namespace {

// A camera 1 m in front of the marker, moved sideways by x metres.
Rigid3 CameraAt(double x) { return Rigid3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(-x, 0, 1)); }

// 10 fps, 3 s: still for 1 s, then moving 0.1 m/s sideways; hidden in frames 15-19.
TrajectoryOptions Trajectory() {
  TrajectoryOptions o;
  o.fps = 10.0;
  o.duration_s = 3.0;
  o.static_s = 1.0;
  o.occlusions = {{15, 19}};
  return o;
}

std::vector<SequenceFrame> Frames(const TrajectoryOptions& o) {
  std::vector<SequenceFrame> frames(o.Frames());
  for (int k = 0; k < o.Frames(); ++k) {
    frames[k].occluded = o.Occluded(k);
    frames[k].truth = CameraAt(0.1 * std::max(0.0, o.TruthTime(k) - o.static_s));
    frames[k].time_ms = 1.0;
  }
  return frames;
}

TEST(SequenceMetrics, ExactTrackingHasNoErrorAndCountsTheOcclusion) {
  const TrajectoryOptions o = Trajectory();
  std::vector<SequenceFrame> frames = Frames(o);
  for (SequenceFrame& f : frames) {
    if (!f.occluded) f.estimate = f.truth;
  }
  const SequenceMetrics m = MeasureSequence(frames, o);
  EXPECT_EQ(m.frames, 30);
  EXPECT_EQ(m.visible, 25);
  EXPECT_EQ(m.lost, 0);
  EXPECT_EQ(m.found_hidden, 0);
  EXPECT_NEAR(m.ate_m, 0.0, 1e-12);
  EXPECT_NEAR(m.rpe_m, 0.0, 1e-12);
  EXPECT_NEAR(m.jitter_m, 0.0, 1e-12);
  ASSERT_EQ(m.reacquire_s.size(), 1u);
  EXPECT_EQ(m.reacquire_s[0], 0.0);
}

// Known errors: a constant 2 mm offset is ATE 2 mm and no RPE; ±1 mm alternating over the
// still start is jitter; found again 3 frames after the occlusion ends is 0.3 s; a
// pose while hidden is a false find; the frames after a pose are the tracking ones.
TEST(SequenceMetrics, KnownErrorsGiveKnownFigures) {
  const TrajectoryOptions o = Trajectory();
  std::vector<SequenceFrame> frames = Frames(o);
  for (int k = 0; k < o.Frames(); ++k) {
    SequenceFrame& f = frames[k];
    f.time_ms = k > 0 && frames[k - 1].estimate ? 1.0 : 5.0;
    if (k >= 20 && k < 23) continue;  // lost for 3 frames after the occlusion
    const double x = 0.1 * std::max(0.0, o.TruthTime(k) - o.static_s);
    const double jitter = k < 10 ? (k % 2 == 0 ? 0.001 : -0.001) : 0.0;
    f.estimate = CameraAt(x + 0.002 + jitter);
  }
  const SequenceMetrics m = MeasureSequence(frames, o);
  EXPECT_EQ(m.lost, 3);
  EXPECT_EQ(m.found_hidden, 5);
  // The still start is frames 0-10 (frame 10's exposure ends at 1 s): ten at ±1 mm, one at 0.
  EXPECT_NEAR(m.jitter_m, 0.001 * std::sqrt(10.0 / 11.0), 1e-12);
  // RMS of 2 mm everywhere but the still start's 1 or 3 mm, over the 27 frames with a pose.
  EXPECT_NEAR(m.ate_m, std::sqrt((5 * 9e-6 + 5 * 1e-6 + 17 * 4e-6) / 27), 1e-12);
  ASSERT_EQ(m.reacquire_s.size(), 1u);
  EXPECT_NEAR(m.reacquire_s[0], 0.3, 1e-12);
  EXPECT_EQ(m.tracking_ms, 1.0);
  EXPECT_EQ(m.detection_ms, 5.0);
  // Pairs 1 s apart whose first frame is in the still start carry its ±1 mm; the rest none.
  EXPECT_GT(m.rpe_m, 0.0);
  EXPECT_LT(m.rpe_m, 0.001 + 1e-12);
  EXPECT_NEAR(m.rpe_deg, 0.0, 1e-9);
}

TEST(SequenceMetrics, NeverFoundAgainIsInfinite) {
  const TrajectoryOptions o = Trajectory();
  std::vector<SequenceFrame> frames = Frames(o);
  for (int k = 0; k < 15; ++k) frames[k].estimate = frames[k].truth;
  const SequenceMetrics m = MeasureSequence(frames, o);
  EXPECT_TRUE(std::isinf(m.reacquire_s.at(0)));
  EXPECT_EQ(m.lost, 10);
}

}  // namespace
}  // namespace markerbench
