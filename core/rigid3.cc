#include "core/rigid3.h"

#include <algorithm>
#include <cmath>

namespace markerbench {

bool IsRotation(const Eigen::Matrix3d& r, double tolerance) {
  return (r.transpose() * r - Eigen::Matrix3d::Identity()).norm() <= tolerance &&
         r.determinant() > 0.0;
}

Eigen::Matrix3d RotationFromVector(const Eigen::Vector3d& v) {
  const double angle = v.norm();
  return angle > 0.0 ? Eigen::AngleAxisd(angle, v / angle).toRotationMatrix()
                     : Eigen::Matrix3d::Identity();
}

double RotationAngleBetween(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  const double cos_angle = ((a.transpose() * b).trace() - 1.0) / 2.0;
  return std::acos(std::clamp(cos_angle, -1.0, 1.0));
}

}  // namespace markerbench
