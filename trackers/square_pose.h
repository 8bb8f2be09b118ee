// Pose of a square marker from its four corners: OpenCV's IPPE_SQUARE (Collins and Bartoli
// 2014) gives both planar-ambiguity hypotheses, each then refined by Levenberg-Marquardt on
// the corners' reprojection error.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "core/camera.h"
#include "core/rigid3.h"

namespace markerbench {

// corners_px in our square order: top-left, top-right, bottom-right, bottom-left of the
// black square (marker frame (-s, s), (s, s), (s, -s), (-s, -s), s = size_m / 2). Returns
// cam_from_marker hypotheses, lowest RMS reprojection error first.
std::vector<Rigid3> SquarePoseHypotheses(const std::array<Eigen::Vector2d, 4>& corners_px,
                                         double size_m,
                                         const Camera& camera);

}  // namespace markerbench
