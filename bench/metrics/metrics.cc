#include "bench/metrics/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/pose_error.h"

namespace markerbench {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kFlipWrongDeg = 30.0;
constexpr double kFlipRightDeg = 5.0;

std::vector<double> WithoutNaN(std::vector<double> values) {
  values.erase(std::remove_if(values.begin(), values.end(), [](double v) { return std::isnan(v); }),
               values.end());
  return values;
}

}  // namespace

int BestHypothesisIndex(const std::vector<Rigid3>& hypotheses, const Rigid3& truth) {
  int best = -1;
  double best_error = 0.0;
  for (size_t i = 0; i < hypotheses.size(); ++i) {
    const double error = RotationErrorDeg(hypotheses[i], truth);
    if (best < 0 || error < best_error) {
      best = static_cast<int>(i);
      best_error = error;
    }
  }
  return best;
}

bool IsFlip(const std::vector<Rigid3>& hypotheses, const Rigid3& truth) {
  if (hypotheses.size() < 2 || RotationErrorDeg(hypotheses[0], truth) <= kFlipWrongDeg) {
    return false;
  }
  return std::any_of(hypotheses.begin() + 1, hypotheses.end(), [&](const Rigid3& h) {
    return RotationErrorDeg(h, truth) <= kFlipRightDeg;
  });
}

PoseErrors ComputePoseErrors(const std::vector<Rigid3>& hypotheses, const Rigid3& truth) {
  PoseErrors e{kNaN, kNaN, kNaN, kNaN, false};
  if (hypotheses.empty()) return e;
  e.position_error_m = PositionError(hypotheses[0], truth);
  e.rotation_error_deg = RotationErrorDeg(hypotheses[0], truth);
  const Rigid3& best = hypotheses[static_cast<size_t>(BestHypothesisIndex(hypotheses, truth))];
  e.best_position_error_m = PositionError(best, truth);
  e.best_rotation_error_deg = RotationErrorDeg(best, truth);
  e.flip = IsFlip(hypotheses, truth);
  return e;
}

double DistanceToMarker(const Rigid3& cam_from_marker, const MarkerSpec& marker) {
  const Eigen::Vector2d center = marker.InkBounds().center();
  return (cam_from_marker * Eigen::Vector3d(center.x(), center.y(), 0.0)).norm();
}

bool IsSuccess(bool has_pose, double position_error_m, double distance_m, double fraction) {
  return has_pose && position_error_m <= fraction * distance_m;
}

double Median(std::vector<double> values) { return Percentile(std::move(values), 50.0); }

double Mean(const std::vector<double>& values) {
  const std::vector<double> numbers = WithoutNaN(values);
  if (numbers.empty()) return kNaN;
  double sum = 0.0;
  for (double v : numbers) sum += v;
  return sum / static_cast<double>(numbers.size());
}

double Percentile(std::vector<double> values, double p) {
  values = WithoutNaN(std::move(values));
  if (values.empty()) return kNaN;
  std::sort(values.begin(), values.end());
  const double rank = p / 100.0 * static_cast<double>(values.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(rank));
  const size_t hi = std::min(lo + 1, values.size() - 1);
  const double fraction = rank - static_cast<double>(lo);
  if (fraction == 0.0 || values[lo] == values[hi]) return values[lo];  // no 0 · ∞
  return values[lo] + fraction * (values[hi] - values[lo]);
}

}  // namespace markerbench
