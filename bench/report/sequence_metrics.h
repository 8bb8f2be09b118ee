// What a tracker does over a video (issue 22), from the frames.csv rows of one sequence
// (bench/plan/trajectory.h): frames lost, finds while the marker is hidden, absolute
// trajectory error, relative pose error over 1 s, jitter over the still start, time to
// re-acquire after each occlusion, and the time per frame while tracking against after a
// loss. Poses are the camera's in the marker frame, as in the TUM files, so that ATE needs no
// alignment (the marker is the world).
#pragma once

#include <optional>
#include <vector>

#include "bench/plan/trajectory_options.h"
#include "core/rigid3.h"

namespace markerbench {

// One frame of a sequence, for one tracker.
struct SequenceFrame {
  bool occluded = false;
  Rigid3 truth;                    // cam_from_marker
  std::optional<Rigid3> estimate;  // the first hypothesis when the status is ok
  double time_ms = 0.0;            // NaN when unknown
};

struct SequenceMetrics {
  int frames = 0;
  int visible = 0;       // frames where the marker is not hidden
  int lost = 0;          // visible frames without a pose
  int found_hidden = 0;  // hidden frames with a pose: false detections
  // Over the frames with a pose (metres, degrees); NaN when there are none.
  double ate_m = NAN;  // RMS camera-position error
  double rpe_m = NAN;  // RMS error of the camera's motion over rpe_interval_s
  double rpe_deg = NAN;
  double jitter_m = NAN;  // RMS deviation of the estimated position over the still start
  // Per occlusion, in order: seconds from the marker's reappearance to the first pose; +inf
  // when it is never found again.
  std::vector<double> reacquire_s;
  // Median time per frame (ms) over the visible frames right after a frame with a pose
  // (tracking) and over the others (the first frame, and after a loss or an occlusion: full
  // detection); NaN when there are none.
  double tracking_ms = NAN;
  double detection_ms = NAN;
};

inline constexpr double kRpeIntervalS = 1.0;

// `frames` in sequence order (frame k at trajectory.TruthTime(k)).
SequenceMetrics MeasureSequence(const std::vector<SequenceFrame>& frames,
                                const TrajectoryOptions& trajectory);

}  // namespace markerbench
