#include "bench/report/sequence_metrics.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "bench/metrics/metrics.h"

namespace markerbench {
namespace {

double RootMean(double sum_of_squares, int n) {
  return n > 0 ? std::sqrt(sum_of_squares / n) : NAN;
}

}  // namespace

SequenceMetrics MeasureSequence(const std::vector<SequenceFrame>& frames,
                                const TrajectoryOptions& trajectory) {
  SequenceMetrics m;
  const int n = static_cast<int>(frames.size());
  m.frames = n;
  double ate_sq = 0.0;
  int posed = 0;
  std::vector<double> tracking, detection;
  for (int k = 0; k < n; ++k) {
    const SequenceFrame& f = frames[k];
    if (f.occluded) {
      m.found_hidden += f.estimate.has_value();
    } else {
      ++m.visible;
      m.lost += !f.estimate.has_value();
    }
    if (f.estimate) {
      ate_sq += (CameraCenterInMarker(*f.estimate) - CameraCenterInMarker(f.truth)).squaredNorm();
      ++posed;
    }
    if (!f.occluded) (k > 0 && frames[k - 1].estimate ? tracking : detection).push_back(f.time_ms);
  }
  m.ate_m = RootMean(ate_sq, posed);
  m.tracking_ms = Median(tracking);
  m.detection_ms = Median(detection);

  // Relative pose error (Sturm et al. 2012) over kRpeIntervalS, on camera poses in the
  // marker frame: E = (Q_k⁻¹ Q_k+Δ)⁻¹ (P_k⁻¹ P_k+Δ), Q the truth and P the estimate.
  const int step = std::max(1, static_cast<int>(std::lround(trajectory.fps * kRpeIntervalS)));
  double rpe_sq = 0.0, rpe_deg_sq = 0.0;
  int pairs = 0;
  for (int k = 0; k + step < n; ++k) {
    const SequenceFrame &a = frames[k], &b = frames[k + step];
    if (!a.estimate || !b.estimate) continue;
    const Rigid3 truth_motion = a.truth * b.truth.Inverse();  // (Q_k⁻¹ Q_k+Δ) with Q = cam⁻¹
    const Rigid3 estimated_motion = *a.estimate * b.estimate->Inverse();
    const Rigid3 error = truth_motion.Inverse() * estimated_motion;
    rpe_sq += error.translation.squaredNorm();
    rpe_deg_sq += std::pow(Eigen::AngleAxisd(error.rotation).angle() * 180.0 / M_PI, 2);
    ++pairs;
  }
  m.rpe_m = RootMean(rpe_sq, pairs);
  m.rpe_deg = RootMean(rpe_deg_sq, pairs);

  // Jitter: over the frames whose every row's exposure falls in the still start.
  std::vector<Eigen::Vector3d> still;
  for (int k = 0; k < n; ++k) {
    if (trajectory.FrameEnd(k) > trajectory.static_s) break;
    if (!frames[k].occluded && frames[k].estimate) {
      still.push_back(CameraCenterInMarker(*frames[k].estimate));
    }
  }
  if (still.size() >= 2) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& c : still) mean += c / static_cast<double>(still.size());
    double spread_sq = 0.0;
    for (const Eigen::Vector3d& c : still) spread_sq += (c - mean).squaredNorm();
    m.jitter_m = RootMean(spread_sq, static_cast<int>(still.size()));
  }

  for (const FrameRange& r : trajectory.occlusions) {
    double seconds = r.last + 1 < n ? INFINITY : NAN;  // NaN: hidden to the end
    for (int k = r.last + 1; k < n; ++k) {
      if (frames[k].estimate) {
        seconds = (k - r.last - 1) / trajectory.fps;
        break;
      }
    }
    m.reacquire_s.push_back(seconds);
  }
  return m;
}

}  // namespace markerbench
