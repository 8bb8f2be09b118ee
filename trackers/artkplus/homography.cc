#include "trackers/artkplus/homography.h"

#include <Eigen/Dense>
#include <cmath>

namespace markerbench {
namespace {

// Similarity moving the points' centroid to the origin with mean distance sqrt(2).
Eigen::Matrix3d Normalizer(const std::vector<Eigen::Vector2d>& points) {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  double spread = 0.0;
  for (const Eigen::Vector2d& p : points) spread += (p - mean).norm();
  const double scale = std::sqrt(2.0) * static_cast<double>(points.size()) / spread;
  Eigen::Matrix3d T;
  T << scale, 0, -scale * mean.x(), 0, scale, -scale * mean.y(), 0, 0, 1;
  return T;
}

}  // namespace

Eigen::Matrix3d HomographyDlt(const std::vector<Eigen::Vector2d>& from,
                              const std::vector<Eigen::Vector2d>& to) {
  const Eigen::Matrix3d T_from = Normalizer(from), T_to = Normalizer(to);
  Eigen::MatrixXd A(2 * from.size(), 9);
  for (size_t i = 0; i < from.size(); ++i) {
    const Eigen::Vector3d x = T_from * from[i].homogeneous();
    const Eigen::Vector3d u = T_to * to[i].homogeneous();
    A.row(2 * i) << Eigen::RowVector3d::Zero(), -u.z() * x.transpose(), u.y() * x.transpose();
    A.row(2 * i + 1) << u.z() * x.transpose(), Eigen::RowVector3d::Zero(), -u.x() * x.transpose();
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  const Eigen::VectorXd h = svd.matrixV().col(8);
  Eigen::Matrix3d H;
  H << h(0), h(1), h(2), h(3), h(4), h(5), h(6), h(7), h(8);
  H = T_to.inverse() * H * T_from;
  return H / H(2, 2);
}

}  // namespace markerbench
