#include "core/camera.h"

#include <cmath>
#include <sstream>

namespace markerbench {

bool Camera::HasDistortion() const {
  for (double d : distortion) {
    if (d != 0.0) return true;
  }
  return false;
}

Eigen::Matrix3d Camera::K() const {
  Eigen::Matrix3d k;
  k << fx, 0.0, cx, 0.0, fy, cy, 0.0, 0.0, 1.0;
  return k;
}

Eigen::Vector2d Camera::Distort(const Eigen::Vector2d& n) const {
  const auto& [k1, k2, p1, p2, k3] = distortion;
  const double x = n.x(), y = n.y();
  const double r2 = x * x + y * y;
  const double radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3));
  return {x * radial + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x),
          y * radial + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y};
}

Eigen::Matrix2d Camera::DistortJacobian(const Eigen::Vector2d& n) const {
  const auto& [k1, k2, p1, p2, k3] = distortion;
  const double x = n.x(), y = n.y();
  const double r2 = x * x + y * y;
  const double radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3));
  const double dradial_dr2 = k1 + r2 * (2.0 * k2 + 3.0 * r2 * k3);  // d(radial)/dx = 2x·this
  Eigen::Matrix2d j;
  j(0, 0) = radial + 2.0 * x * x * dradial_dr2 + 2.0 * p1 * y + 6.0 * p2 * x;
  j(0, 1) = 2.0 * x * y * dradial_dr2 + 2.0 * p1 * x + 2.0 * p2 * y;
  j(1, 0) = 2.0 * x * y * dradial_dr2 + 2.0 * p1 * x + 2.0 * p2 * y;
  j(1, 1) = radial + 2.0 * y * y * dradial_dr2 + 6.0 * p1 * y + 2.0 * p2 * x;
  return j;
}

Eigen::Vector2d Camera::Undistort(const Eigen::Vector2d& distorted) const {
  if (!HasDistortion()) return distorted;
  constexpr int kMaxIterations = 20;
  constexpr double kTolerance = 1e-14;  // normalized units, far below 1e-6 px
  Eigen::Vector2d n = distorted;
  for (int i = 0; i < kMaxIterations; ++i) {
    const Eigen::Vector2d residual = Distort(n) - distorted;
    if (residual.squaredNorm() < kTolerance * kTolerance) break;
    n -= DistortJacobian(n).inverse() * residual;
  }
  return n;
}

Eigen::Vector2d Camera::ImgFromCam(const Eigen::Vector3d& x_cam) const {
  const Eigen::Vector2d d = Distort(x_cam.head<2>() / x_cam.z());
  return {fx * d.x() + cx, fy * d.y() + cy};
}

Eigen::Vector2d Camera::IdealFromCam(const Eigen::Vector3d& x_cam) const {
  return {fx * (x_cam.x() / x_cam.z()) + cx, fy * (x_cam.y() / x_cam.z()) + cy};
}

Eigen::Vector3d Camera::CamFromIdeal(const Eigen::Vector2d& ideal_px) const {
  return {(ideal_px.x() - cx) / fx, (ideal_px.y() - cy) / fy, 1.0};
}

// The pinhole's ray through the pixel is the distorted point Undistort takes.
Eigen::Vector3d Camera::CamFromImg(const Eigen::Vector2d& px) const {
  const Eigen::Vector2d n = Undistort(CamFromIdeal(px).head<2>());
  return {n.x(), n.y(), 1.0};
}

Eigen::Vector2d Camera::IdealFromImg(const Eigen::Vector2d& px) const {
  return IdealFromCam(CamFromImg(px));
}

Eigen::Vector2d Camera::ImgFromIdeal(const Eigen::Vector2d& ideal_px) const {
  return ImgFromCam(CamFromIdeal(ideal_px));
}

Eigen::Matrix2d Camera::IdealFromImgJacobian(const Eigen::Vector3d& ray) const {
  const Eigen::Vector2d f(fx, fy);
  return f.asDiagonal() * DistortJacobian(ray.head<2>()).inverse() * f.cwiseInverse().asDiagonal();
}

bool Camera::IsValid(std::string* error) const {
  std::ostringstream msg;
  if (width <= 0 || height <= 0) {
    msg << "image size " << width << "x" << height << " must be positive";
  } else if (!(fx > 0.0) || !(fy > 0.0)) {
    msg << "focal lengths fx=" << fx << ", fy=" << fy << " must be positive";
  } else if (!std::isfinite(cx) || !std::isfinite(cy)) {
    msg << "principal point must be finite";
  } else {
    return true;
  }
  if (error) *error = msg.str();
  return false;
}

}  // namespace markerbench
