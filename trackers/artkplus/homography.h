// The plane-to-plane homography H with to ~ H from, by the normalized DLT (Hartley and
// Zisserman, Alg. 4.2) over n >= 4 correspondences.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace markerbench {

Eigen::Matrix3d HomographyDlt(const std::vector<Eigen::Vector2d>& from,
                              const std::vector<Eigen::Vector2d>& to);

}  // namespace markerbench
