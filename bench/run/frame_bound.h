// The Cramér-Rao bound of a frame (renderer/pose_crlb.h) as a run gives it: the same columns in
// frames.csv and in a rendered dataset's groundtruth.csv, so that a tracker scored offline
// (`markerbench score`) is compared with the bound of the very frames it saw.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <string>
#include <vector>

#include "bench/plan/frame_plan.h"
#include "bench/run/frames_csv.h"
#include "renderer/pose_crlb.h"

namespace markerbench {

// NaN (an empty field): not computed. Infinite: nothing to see (the marker hidden, or a pose
// direction the image does not show).
struct FrameBound {
  double position_m = NAN;      // RMS of the camera centre's error
  double position_med_m = NAN;  // its median
  double rotation_deg = NAN;
  double rotation_med_deg = NAN;
  Eigen::Vector3d position_variances_m2 = Eigen::Vector3d::Constant(NAN);
};

FrameBound BoundOf(const PoseBound& bound);

// A planned frame's: infinite where the marker is hidden, NaN where the scenario does not ask
// for the bound (crlb: false), else PoseCrlb of its request.
FrameBound PlannedFrameBound(const Scenario& scenario,
                             const PlannedFrame& frame,
                             const FrameRequest& request);

// The columns, as frames.csv names them.
const std::vector<std::string>& FrameBoundColumns();
// Its fields in those columns, each after a comma.
std::string FrameBoundFields(const FrameBound& bound);
void SetFrameBound(const FrameBound& bound, FrameRow* row);

}  // namespace markerbench
