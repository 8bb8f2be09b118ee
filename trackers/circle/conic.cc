#include "trackers/circle/conic.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>

namespace markerbench {

Eigen::Matrix3d Adjugate(const Eigen::Matrix3d& C) {
  Eigen::Matrix3d cofactor;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      const int r0 = (r + 1) % 3, r1 = (r + 2) % 3, c0 = (c + 1) % 3, c1 = (c + 2) % 3;
      cofactor(r, c) = C(r0, c0) * C(r1, c1) - C(r0, c1) * C(r1, c0);
    }
  }
  return cofactor.transpose();
}

Eigen::Matrix3d CanonicalConic(const Eigen::Matrix3d& C) {
  Eigen::Matrix3d S = 0.5 * (C + C.transpose());
  S /= S.norm();
  if (S(0, 0) + S(1, 1) < 0.0) S = -S;
  return S;
}

bool IsRealEllipse(const Eigen::Matrix3d& C) {
  const Eigen::Matrix3d S = CanonicalConic(C);
  const double det_a = S(0, 0) * S(1, 1) - S(0, 1) * S(1, 0);
  return std::isfinite(det_a) && det_a > 0.0 && S.determinant() < 0.0;
}

Ellipse EllipseFromConic(const Eigen::Matrix3d& C) {
  const Eigen::Matrix2d A = C.topLeftCorner<2, 2>();
  const Eigen::Vector2d b = C.topRightCorner<2, 1>();
  Ellipse e;
  e.center = -A.inverse() * b;
  const double k = -(C(2, 2) + b.dot(e.center));
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(A / k);
  // Ascending eigenvalues: the smallest belongs to the major axis.
  e.semi_major = 1.0 / std::sqrt(eig.eigenvalues()(0));
  e.semi_minor = 1.0 / std::sqrt(eig.eigenvalues()(1));
  const Eigen::Vector2d major = eig.eigenvectors().col(0);
  e.angle_rad = std::atan2(major.y(), major.x());
  return e;
}

double PndReach(const Ellipse& e, double distance) {
  const double eccentricity = e.semi_major / e.semi_minor;
  const double reach = 1.000001 * e.semi_major + 2.01 * distance * eccentricity * eccentricity;
  return std::isnan(reach) ? INFINITY : reach;  // axes lost to rounding: skip nothing
}

PndBand PndBandScales(const Ellipse& e, double distance) {
  if (std::isnan(e.semi_major) || std::isnan(e.semi_minor)) return {};
  const double per_minor = 1.01 * distance / e.semi_minor;
  return {std::max(0.0, 0.999999 * (1.0 - per_minor)),
          1.000001 * (per_minor + std::sqrt(per_minor * per_minor + 1.0))};
}

Eigen::Matrix2d EllipseForm(const Ellipse& ellipse) {
  const double c = std::cos(ellipse.angle_rad), s = std::sin(ellipse.angle_rad);
  Eigen::Matrix2d rot;
  rot << c, -s, s, c;
  return rot *
         Eigen::Vector2d(1.0 / (ellipse.semi_major * ellipse.semi_major),
                         1.0 / (ellipse.semi_minor * ellipse.semi_minor))
             .asDiagonal() *
         rot.transpose();
}

Eigen::Matrix3d ConicFromEllipse(const Ellipse& ellipse) {
  const Eigen::Matrix2d A = EllipseForm(ellipse);
  Eigen::Matrix3d C;
  C.topLeftCorner<2, 2>() = A;
  C.topRightCorner<2, 1>() = -A * ellipse.center;
  C.bottomLeftCorner<1, 2>() = (-A * ellipse.center).transpose();
  C(2, 2) = ellipse.center.dot(A * ellipse.center) - 1.0;
  return CanonicalConic(C);
}

bool LineMissesEllipse(const Eigen::Vector3d& l, const Eigen::Matrix3d& C) {
  return l.dot(Adjugate(C) * l) > 0.0;
}

}  // namespace markerbench
