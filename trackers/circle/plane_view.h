// Pixels seen on a marker plane through a pose: the plane point each pixel looks at, and how
// that point moves with the pixel (the local map of blurred_design.h).
#pragma once

#include <Eigen/Core>

#include "core/camera.h"
#include "core/image.h"
#include "core/rigid3.h"

namespace markerbench {

struct PlaneLook {
  Eigen::Vector2d point = Eigen::Vector2d::Zero();
  // d(point)/d(pixel), through the lens.
  Eigen::Matrix2d plane_from_px = Eigen::Matrix2d::Zero();
  // The plane's homogeneous scale along the ray: positive in front of the camera; an ideal
  // (pinhole) pixel covers |det plane_from_ray| / (fx fy homogeneous³) of the plane.
  double homogeneous = 0.0;
  // The ideal pixels' area a pixel spans (Camera::IdealFromImgJacobian's determinant): 1 without
  // distortion; through cameras/wide_distorted.yaml 2.3 at the image's sides, 4.7 at its corners.
  double ideal_area_per_px = 1.0;
};

class PlaneView {
 public:
  PlaneView(const Camera& camera, const Rigid3& cam_from_plane);

  // What pixel (x, y) of the (distorted) image sees.
  PlaneLook Look(double x, double y) const;
  // The same for the pixel whose ray, z = 1, is `ray` (Camera::CamFromImg).
  PlaneLook LookAlong(const Eigen::Vector3d& ray) const;

  const Eigen::Matrix3d& plane_from_ray() const { return plane_from_ray_; }

 private:
  const Camera& camera_;
  bool has_distortion_;  // cached: LookAlong runs per pixel
  Eigen::Matrix3d plane_from_ray_;
  Eigen::Matrix3d plane_from_px_;  // from ideal pixels: plane_from_ray K⁻¹
};

// A pixel's luma, 0-255 (Rec. 601 for RGB).
double LumaAt(const Image8& image, int x, int y);

}  // namespace markerbench
