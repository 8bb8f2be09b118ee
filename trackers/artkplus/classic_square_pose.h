// The classic ARToolKit pose (arGetTransMat; Kato and Billinghurst, IWAR 1999), the
// original's alternative to Robust Planar Pose: the rotation from the vanishing directions of
// the square's two pairs of opposite sides, the translation by linear least squares, then a
// coordinate search over three small rotations about the marker axes (arModifyMatrix) that
// lowers the reprojection error, halving the step when no neighbour improves.
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>

#include "core/rigid3.h"

namespace markerbench {

struct ClassicSquarePoseOptions {
  int max_loops = 5;              // search passes (the original's AR_GET_TRANS_MAT_MAX_LOOP_COUNT)
  double initial_step_deg = 5.0;  // first step of each pass
  double min_step_deg = 0.005;    // a pass ends when the step falls below this
};

// rays: the undistorted normalized image coordinates (x/z, y/z) of the square's corners in
// our order top-left, top-right, bottom-right, bottom-left (marker frame (-s, s), (s, s),
// (s, -s), (-s, -s), s = size_m / 2). nullopt when opposite sides give no direction.
std::optional<Rigid3> ClassicSquarePose(const std::array<Eigen::Vector2d, 4>& rays,
                                        double size_m,
                                        const ClassicSquarePoseOptions& options = {});

}  // namespace markerbench
