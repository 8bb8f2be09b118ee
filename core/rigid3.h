// Rigid transforms named by their frames (COLMAP style): x_b = b_from_a * x_a, and
// c_from_a = c_from_b * b_from_a. See architecture.md, "Pose".
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace markerbench {

struct Rigid3 {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  Rigid3() = default;
  Rigid3(const Eigen::Matrix3d& rotation_in, const Eigen::Vector3d& translation_in)
      : rotation(rotation_in), translation(translation_in) {}

  // a_from_b for this b_from_a.
  Rigid3 Inverse() const { return {rotation.transpose(), -rotation.transpose() * translation}; }

  Eigen::Vector3d operator*(const Eigen::Vector3d& x_a) const {
    return rotation * x_a + translation;
  }

  // c_from_a = (*this = c_from_b) * b_from_a.
  Rigid3 operator*(const Rigid3& b_from_a) const {
    return {rotation * b_from_a.rotation, rotation * b_from_a.translation + translation};
  }
};

// The camera centre in the marker frame, -Rᵀt (the paper's localization target).
inline Eigen::Vector3d CameraCenterInMarker(const Rigid3& cam_from_marker) {
  return -cam_from_marker.rotation.transpose() * cam_from_marker.translation;
}

// Whether the marker's origin is in front of the camera and the camera on the marker's
// printed side (+z). Negating r1, r2 and t leaves the image of the plane the same, [r1 r2 t]
// up to scale, but fails this.
inline bool FacesTheCamera(const Rigid3& cam_from_marker) {
  return cam_from_marker.translation.z() > 0.0 && CameraCenterInMarker(cam_from_marker).z() > 0.0;
}

// [r1 r2 t]: the homography from the marker plane's points (X, Y, 1) (z = 0) to their rays
// (x, y, z) in the camera frame; K times it maps them to pixels (circle-method.md §0).
inline Eigen::Matrix3d RayFromPlane(const Rigid3& cam_from_marker) {
  Eigen::Matrix3d H;
  H << cam_from_marker.rotation.col(0), cam_from_marker.rotation.col(1),
      cam_from_marker.translation;
  return H;
}

// Whether `r` is a rotation within `tolerance`: ||RᵀR − I|| (Frobenius) <= tolerance and
// det R > 0 (a matrix with a NaN is none). For rotations read from text or other programs.
bool IsRotation(const Eigen::Matrix3d& r, double tolerance = 1e-6);

// The rotation by |v| radians about v (the exponential map of the rotation vector v); the
// identity for v = 0.
Eigen::Matrix3d RotationFromVector(const Eigen::Vector3d& v);

// Angle of the relative rotation between two rotations, in radians, in [0, π].
double RotationAngleBetween(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b);

}  // namespace markerbench
