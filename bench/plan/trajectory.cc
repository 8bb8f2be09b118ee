#include "bench/plan/trajectory.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace markerbench {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

// Scales `axes` so that the time average of the squared speed over them is speed².
void ScaleToSpeed(double speed, std::array<Shake::Sinusoid, Shake::kComponents>* axes, int count) {
  double mean_square = 0.0;  // of Σ A 2πf cos(...): Σ (A 2πf)² / 2 for distinct frequencies
  for (int a = 0; a < count; ++a) {
    for (const Shake::Sinusoid& s : axes[a]) {
      mean_square += 0.5 * std::pow(2.0 * kPi * s.hertz * s.amplitude, 2);
    }
  }
  const double factor = mean_square > 0.0 ? speed / std::sqrt(mean_square) : 0.0;
  for (int a = 0; a < count; ++a) {
    for (Shake::Sinusoid& s : axes[a]) s.amplitude *= factor;
  }
}

}  // namespace

int TrajectoryOptions::Frames() const {
  return std::max(1, static_cast<int>(std::lround(fps * duration_s)));
}

bool TrajectoryOptions::Occluded(int frame) const {
  return std::any_of(occlusions.begin(), occlusions.end(), [&](const FrameRange& r) {
    return frame >= r.first && frame <= r.last;
  });
}

double TrajectoryOptions::FrameTime(int frame) const { return frame / fps; }

const char* TrajectoryKindName(TrajectoryKind kind) {
  switch (kind) {
    case TrajectoryKind::kOrbit:
      return "orbit";
    case TrajectoryKind::kApproach:
      return "approach";
    default:
      return "handheld";
  }
}

Shake Shake::Draw(double linear_speed_m_s, double angular_speed_deg_s, Rng* rng) {
  Shake shake;
  for (auto& axis : shake.axes) {
    for (Sinusoid& s : axis) {
      s.amplitude = rng->Uniform(0.5, 1.0);
      s.hertz = rng->Uniform(0.2, 1.5);  // a hand's shake and sway
      s.phase = rng->Uniform(0.0, 2.0 * kPi);
    }
  }
  ScaleToSpeed(linear_speed_m_s, shake.axes.data(), 3);
  ScaleToSpeed(angular_speed_deg_s * kDeg, shake.axes.data() + 3, 3);
  return shake;
}

std::array<double, 6> Shake::At(double t) const {
  std::array<double, 6> x{};
  for (size_t a = 0; a < axes.size(); ++a) {
    for (const Sinusoid& s : axes[a])
      x[a] += s.amplitude * std::sin(2.0 * kPi * s.hertz * t + s.phase);
  }
  return x;
}

Rigid3 Shake::MotionAt(double t) const {
  const std::array<double, 6> x = At(t);
  return Rigid3(RotationFromVector(Eigen::Vector3d(x[3], x[4], x[5])),
                Eigen::Vector3d(x[0], x[1], x[2]));
}

Rigid3 TrajectoryPose(const TrajectoryOptions& o,
                      const TrialTrajectory& trial,
                      const Camera& camera,
                      double t) {
  const double moving = std::max(0.0, t - o.static_s);  // time since the camera started moving
  LookAt look_at = trial.start;
  switch (o.kind) {
    case TrajectoryKind::kOrbit:
      look_at.azimuth += o.degrees_per_s * kDeg * moving;
      return LookAtPose(look_at, camera);
    case TrajectoryKind::kApproach: {
      const double span = std::max(o.duration_s - o.static_s, 1e-9);
      const double from_m = trial.start.distance_m;
      look_at.distance_m = from_m + (o.to_m - from_m) * std::min(1.0, moving / span);
      return LookAtPose(look_at, camera);
    }
    default:
      return trial.shake.MotionAt(moving).Inverse() * LookAtPose(look_at, camera);
  }
}

TrialTrajectory SampleTrialTrajectory(const TrajectoryOptions& options,
                                      const PoseSamplerOptions& poses,
                                      const Camera& camera,
                                      const std::vector<MarkerSpec>& markers,
                                      uint64_t pose_seed,
                                      uint64_t motion_seed) {
  TrialTrajectory trial;
  Rng motion(motion_seed);
  trial.shake = Shake::Draw(options.linear_speed_m_s, options.angular_speed_deg_s, &motion);
  Rng rng(pose_seed);
  for (int draw = 0; draw < kMaxPoseDraws; ++draw) {
    trial.start = DrawLookAt(poses, &rng);
    bool fits = true;
    for (int k = 0; fits && k < options.Frames(); ++k) {
      for (const double t : {options.FrameTime(k), options.FrameEnd(k)}) {
        fits = fits &&
               MarkersFitInImage(
                   markers, camera, TrajectoryPose(options, trial, camera, t), poses.border_px);
      }
    }
    if (fits) return trial;
  }
  throw std::runtime_error(std::string("no start in 1000 draws keeps every marker inside the "
                                       "image along the ") +
                           TrajectoryKindName(options.kind) +
                           " trajectory; slow it down, shorten it or move the camera back");
}

}  // namespace markerbench
