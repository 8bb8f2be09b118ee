// Pinhole camera with OpenCV's 5-parameter distortion (k1 k2 p1 p2 k3).
// Pixels follow architecture.md: the top-left pixel's centre is (0, 0), u right, v down.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <array>
#include <string>

namespace markerbench {

struct Camera {
  std::string name = "default";
  int width = 640;
  int height = 480;
  double fx = 600.0;
  double fy = 600.0;
  double cx = 319.5;
  double cy = 239.5;
  // OpenCV order: k1, k2, p1, p2, k3.
  std::array<double, 5> distortion{};

  bool HasDistortion() const;
  Eigen::Matrix3d K() const;

  // Pixel of a camera-frame point (z > 0), distortion applied.
  Eigen::Vector2d ImgFromCam(const Eigen::Vector3d& x_cam) const;
  // Undistorted normalized ray (x, y, 1) through a pixel; inverse of ImgFromCam up to scale.
  Eigen::Vector3d CamFromImg(const Eigen::Vector2d& px) const;
  // The pinhole K alone, without the lens: the ideal pixel of a camera-frame point (z > 0), and
  // the ray (x, y, 1) K⁻¹ gives an ideal pixel.
  Eigen::Vector2d IdealFromCam(const Eigen::Vector3d& x_cam) const;
  Eigen::Vector3d CamFromIdeal(const Eigen::Vector2d& ideal_px) const;
  // The ideal pixel of a pixel: where the pinhole K alone images the ray through it (the lens's
  // distortion removed), IdealFromCam(CamFromImg(px)). Computed the same way without distortion,
  // where it is px up to rounding.
  Eigen::Vector2d IdealFromImg(const Eigen::Vector2d& px) const;
  // The pixel through the lens of an ideal pixel, ImgFromCam(CamFromIdeal(ideal_px)); inverse of
  // IdealFromImg.
  Eigen::Vector2d ImgFromIdeal(const Eigen::Vector2d& ideal_px) const;
  // IdealFromImg's Jacobian at the pixel whose ray is `ray` (CamFromImg's, z = 1): the lens's
  // local map, diag(f) J⁻¹ diag(1/f) with J = DistortJacobian: near a barrel lens's sides a
  // pixel spans more than one ideal pixel.
  Eigen::Matrix2d IdealFromImgJacobian(const Eigen::Vector3d& ray) const;

  // Distortion on normalized coordinates, its 2x2 Jacobian, and its inverse (Newton).
  Eigen::Vector2d Distort(const Eigen::Vector2d& undistorted) const;
  Eigen::Matrix2d DistortJacobian(const Eigen::Vector2d& undistorted) const;
  Eigen::Vector2d Undistort(const Eigen::Vector2d& distorted) const;

  // Checks sizes and focal lengths; the message names the field, value and constraint.
  bool IsValid(std::string* error) const;
};

}  // namespace markerbench
