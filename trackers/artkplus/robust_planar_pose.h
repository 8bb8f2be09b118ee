// Robust Planar Pose (Schweighofer and Pinz, PAMI 28(12) 2006), ARToolKitPlus's default pose
// estimator: Lu-Hager-Mjolsness orthogonal iteration (PAMI 22(6) 2000) minimizing the
// object-space error
//   E(R, t) = sum_i |(I - F_i)(R p_i + t)|^2,  F_i = v_i v_i^T / (v_i^T v_i)   (LHM eq. 17)
// from a homography start, then the second local minimum of E that planar targets have.
// Deliberate difference: Schweighofer and Pinz locate the second minimum's tilt as a root of
// a quartic in tan(beta/2); we start orthogonal iteration from the first solution with its
// plane normal mirrored about the line of sight to the points (the two-fold ambiguity that
// the quartic parametrizes), which converges to the same minimum. And each run ends with
// Gauss-Newton on E (OI alone would need hundreds of iterations to converge).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/rigid3.h"

namespace markerbench {

struct RobustPlanarPoseOptions {
  // Orthogonal iteration converges linearly (hundreds of steps for a square), so after at
  // most max_iterations steps Gauss-Newton on the same E finishes the job (our addition).
  int max_iterations = 20;
  int max_polish_steps = 20;
  double relative_tolerance = 1e-12;  // stop when E falls by less than this fraction
};

struct PlanarPoseHypothesis {
  Rigid3 cam_from_marker;
  double object_space_error = 0.0;  // E at the minimum, m^2
  int iterations = 0;
};

// marker_xy: points on the marker plane z = 0 (n >= 4, not collinear); rays: their
// undistorted normalized image coordinates (x/z, y/z). Returns the distinct local minima,
// lower object-space error first (one or two).
std::vector<PlanarPoseHypothesis> RobustPlanarPose(const std::vector<Eigen::Vector2d>& marker_xy,
                                                   const std::vector<Eigen::Vector2d>& rays,
                                                   const RobustPlanarPoseOptions& options = {});

}  // namespace markerbench
