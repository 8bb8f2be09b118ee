// Camera trajectories for sequence scenarios (`trajectory:`, issue 22): a trial is a video
// of duration_s at fps instead of one frame. Each starts from the trial's look-at draw
// (bench/plan/pose_sampler.h) and moves from there:
// - orbit: the azimuth turns at degrees_per_s about the marker's normal, distance and tilt
//   kept;
// - approach: the distance goes linearly from the start's (poses.distance_m) to to_m;
// - handheld: a seeded smooth random shake about the start pose, with the given RMS linear
//   and angular speeds (a sum of sinusoids per axis: band-limited, so the marker stays in
//   view, and smooth, so a tracker's prediction has something to predict).
// The camera holds still for the first static_s seconds (the jitter segment). Frame k's first
// row starts its exposure at k / fps; with exposure_s > 0 each row integrates the motion over
// its exposure, with readout_s > 0 row v starts readout_s × v / (height - 1) late (a rolling
// shutter), and the ground truth is the pose when the middle row is at mid-exposure.
#pragma once

#include <array>
#include <vector>

#include "bench/plan/pose_sampler.h"
#include "bench/plan/trajectory_options.h"
#include "core/random.h"
#include "core/rigid3.h"

namespace markerbench {

// The handheld shake: per axis (3 of translation in the camera frame, 3 of rotation),
// kComponents sinusoids with seeded frequencies and phases, scaled to the RMS speeds.
struct Shake {
  static constexpr int kComponents = 4;
  struct Sinusoid {
    double amplitude = 0.0;
    double hertz = 0.0;
    double phase = 0.0;
  };
  std::array<std::array<Sinusoid, kComponents>, 6> axes{};

  static Shake Draw(double linear_speed_m_s, double angular_speed_deg_s, Rng* rng);
  // (translation in metres, rotation vector in radians) at time t.
  std::array<double, 6> At(double t) const;
  // The same as a move of the camera in its start frame: cam_from_center(t) =
  // MotionAt(t)⁻¹ · cam_from_center(0).
  Rigid3 MotionAt(double t) const;
};

// A trial's trajectory: its start and, for handheld, its shake.
struct TrialTrajectory {
  LookAt start;
  Shake shake;
};

// cam_from_center at time t (seconds from the sequence's start).
Rigid3 TrajectoryPose(const TrajectoryOptions& options,
                      const TrialTrajectory& trial,
                      const Camera& camera,
                      double t);

// The trial's trajectory: starts drawn from the pose stream `pose_seed` (as
// SamplePairedPose draws them) until every marker is whole in the image at the start and end
// of every frame's exposure; the shake from `motion_seed`. Throws std::runtime_error after
// 1000 draws.
TrialTrajectory SampleTrialTrajectory(const TrajectoryOptions& options,
                                      const PoseSamplerOptions& poses,
                                      const Camera& camera,
                                      const std::vector<MarkerSpec>& markers,
                                      uint64_t pose_seed,
                                      uint64_t motion_seed);

}  // namespace markerbench
