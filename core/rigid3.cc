#include "core/rigid3.h"

#include <algorithm>
#include <cmath>

namespace markerbench {

double RotationAngleBetween(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  const double cos_angle = ((a.transpose() * b).trace() - 1.0) / 2.0;
  return std::acos(std::clamp(cos_angle, -1.0, 1.0));
}

}  // namespace markerbench
