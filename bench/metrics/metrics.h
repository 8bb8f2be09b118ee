// Per-frame and per-cell metrics (architecture.md, "Per-frame results" and "Summary"), as
// small documented functions in the style of the BOP toolkit. Poses are cam_from_marker.
#pragma once

#include <vector>

#include "core/marker_spec.h"
#include "core/rigid3.h"

namespace markerbench {

// Errors of one tracker call against the truth; NaN (and no flip) when there is no pose.
struct PoseErrors {
  double position_error_m;       // first hypothesis: camera-centre distance (paper's metric)
  double rotation_error_deg;     // first hypothesis
  double best_position_error_m;  // the oracle: the hypothesis with the least rotation error
  double best_rotation_error_deg;
  bool flip = false;  // see IsFlip
};

// Index of the hypothesis with the least rotation error (an oracle that resolves the planar
// ambiguity with the ground truth); -1 when there is none.
int BestHypothesisIndex(const std::vector<Rigid3>& hypotheses, const Rigid3& truth);

// A flip: the first hypothesis is off by more than 30° while another is within 5° (the
// tracker had the right pose and ranked the mirrored one first).
bool IsFlip(const std::vector<Rigid3>& hypotheses, const Rigid3& truth);

PoseErrors ComputePoseErrors(const std::vector<Rigid3>& hypotheses, const Rigid3& truth);

// The true distance from the camera centre to the centre of the marker's ink bounds
// (frames.csv's distance_m).
double DistanceToMarker(const Rigid3& cam_from_marker, const MarkerSpec& marker);

// Success (experiments.md): a pose, with a position error of at most
// `fraction` × the true camera-to-marker distance; the experiments' fraction is kSuccessFraction.
inline constexpr double kSuccessFraction = 0.1;
bool IsSuccess(bool has_pose, double position_error_m, double distance_m, double fraction);

// Order statistics over the entries of `values` that are not NaN (NaN: no value; +inf, e.g.
// an unobservable frame's bound, sorts last); NaN when there are none. Percentile
// interpolates linearly between order statistics (numpy's default), p in [0, 100].
double Median(std::vector<double> values);
double Mean(const std::vector<double>& values);
double Percentile(std::vector<double> values, double p);

}  // namespace markerbench
