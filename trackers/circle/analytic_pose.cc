#include "trackers/circle/analytic_pose.h"

#include <Eigen/Geometry>
#include <cmath>

namespace markerbench {

std::optional<AnalyticPose> AnalyticPoseFromLine(const Eigen::Vector3d& l_inf,
                                                 const Eigen::Vector3d& m0,
                                                 const Eigen::Vector3d& m1,
                                                 double Lx) {
  const Eigen::Vector3d n01 = m0.cross(m1);
  const double n01_sq = n01.squaredNorm();
  const Eigen::Vector3d v = n01.cross(l_inf);  // eq. 5: may be at infinity; never dehomogenized
  if (!(n01_sq > 1e-24) || !(v.norm() > 1e-15 * n01.norm() * l_inf.norm())) return std::nullopt;
  Eigen::Vector3d r1 = v.normalized();  // eq. 6
  AnalyticPose pose;
  pose.s0 = Lx * m1.cross(r1).dot(n01) / n01_sq;  // eq. 9, least squares
  if (pose.s0 < 0.0) {                            // sign rule 1: m0 in front of the camera
    r1 = -r1;
    pose.s0 = -pose.s0;
  }
  pose.s1 = Lx * m0.cross(r1).dot(n01) / n01_sq;  // eq. 10, least squares
  Eigen::Vector3d r3 = l_inf.normalized();        // eqs. 11-12
  if (r3.dot(m0) > 0.0) r3 = -r3;                 // sign rule 2: camera on the +Z side
  const Eigen::Vector3d r2 = r3.cross(r1);        // eq. 13
  pose.cam_from_paper.rotation.col(0) = r1;
  pose.cam_from_paper.rotation.col(1) = r2;
  pose.cam_from_paper.rotation.col(2) = r3;
  pose.cam_from_paper.translation = pose.s0 * m0;  // eq. 4
  return pose;
}

double DepthFromRadius(const Eigen::Matrix3d& C,
                       const Eigen::Vector3d& r1,
                       const Eigen::Vector3d& r2,
                       const Eigen::Vector3d& m,
                       double radius) {
  return radius * std::sqrt(-(r1.dot(C * r1) + r2.dot(C * r2)) / (2.0 * m.dot(C * m)));
}

}  // namespace markerbench
