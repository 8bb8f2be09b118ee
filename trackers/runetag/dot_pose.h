// Pose from the matched dots of a RUNETag-style marker (baselines.md). The original's
// findPose (the defaults): cv::solvePnP (iterative) on every dot. Ours (runetag-improved):
// RANSAC over the dot correspondences with IPPE on 4 of them inside, LM on the inliers (kept
// within 3 robust sigmas of the fit), then the paper's refinement: each measured dot centre
// is the centre of an ellipse, not the image of the dot's centre (circle-method.md §4.6), so
// it is moved by the offset between the two under the current pose, and LM is run again,
// refinement_passes times.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/camera.h"
#include "core/rigid3.h"

namespace markerbench {

struct DotPoseOptions {
  bool ransac = false;  // the original's RANSAC loop is compiled out (markerpose.cpp)
  int ransac_iterations = 100;
  double ransac_reprojection_px = 2.0;
  // The perspective-bias iterations: 5 in the paper, off in the original's default findPose.
  int refinement_passes = 0;
  uint64_t ransac_seed = 1;  // every call restarts from it (reproducible)
};

struct DotPose {
  Rigid3 cam_from_marker;
  int inliers = 0;
  double rms_px = 0.0;  // reprojection RMS of the inliers after refinement
};

// centers_px: measured (ellipse) centres, distorted pixels; dots_xy and dot_radii_m: the
// dots' centres and radii in the marker plane. Needs 4 or more dots.
std::optional<DotPose> EstimateDotPose(const std::vector<Eigen::Vector2d>& centers_px,
                                       const std::vector<Eigen::Vector2d>& dots_xy,
                                       const std::vector<double>& dot_radii_m,
                                       const Camera& camera,
                                       const DotPoseOptions& options);

}  // namespace markerbench
