// The closed-form pose of Tang and Wu (paper eqs. 3-13) as corrected in circle-method.md §5.2:
// both sign rules (errata 1-2), normalized coordinates (erratum 3) and the least-squares s0/s1.
// The pose is in the paper's frame: origin at m0, +X towards m1 = (Lx, 0, 0), +Z towards the
// camera.
#pragma once

#include <Eigen/Core>
#include <optional>

#include "core/rigid3.h"

namespace markerbench {

struct AnalyticPose {
  Rigid3 cam_from_paper;
  double s0 = 0.0;  // depth of m0 (= t_z)
  double s1 = 0.0;  // depth of m1
};

// l_inf, m0, m1 in normalized coordinates (m0, m1 with w = 1); Lx in metres. nullopt for an
// edge-on view (m0 × m1 ≈ 0 or a vanishing point of X undefined).
std::optional<AnalyticPose> AnalyticPoseFromLine(const Eigen::Vector3d& l_inf,
                                                 const Eigen::Vector3d& m0,
                                                 const Eigen::Vector3d& m1,
                                                 double Lx);

// Depth s of a circle's centre X = s m from its radius (§5.3): r1, r2 any orthonormal pair in
// the plane, C the normalized conic, m its imaged centre (w = 1). Invariant to C's scale/sign.
double DepthFromRadius(const Eigen::Matrix3d& C,
                       const Eigen::Vector3d& r1,
                       const Eigen::Vector3d& r2,
                       const Eigen::Vector3d& m,
                       double radius);

}  // namespace markerbench
