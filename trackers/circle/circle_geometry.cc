#include "trackers/circle/circle_geometry.h"

#include <cmath>

#include "trackers/circle/conic.h"

namespace markerbench {

std::optional<CircleGeometry> CircleGeometryOf(const MarkerSpec& marker, std::string* error) {
  CircleGeometry geometry;
  switch (marker.kind) {
    case MarkerKind::kCirclesA:
    case MarkerKind::kCirclesB:
      geometry.layout = CircleLayout::kTwoCircles;
      break;
    case MarkerKind::kCirclesC:
      geometry.layout = CircleLayout::kConcentric;
      break;
    case MarkerKind::kCircleD:
      geometry.layout = CircleLayout::kCircleWithCenter;
      break;
    case MarkerKind::kCircleE:
      geometry.layout = CircleLayout::kCircleWithCenter;
      geometry.roll_from_design = true;
      break;
    case MarkerKind::kCircleF:
      geometry.layout = CircleLayout::kSingleCircle;
      geometry.roll_from_design = true;
      break;
    default:
      if (error)
        *error = std::string(
                     "the circle tracker supports circles_a, circles_b, circles_c "
                     "and circle_d, circle_e, circle_f, not ") +
                 ToString(marker.kind);
      return std::nullopt;
  }
  const size_t expected_circles =
      geometry.layout == CircleLayout::kTwoCircles || geometry.layout == CircleLayout::kConcentric
          ? 2
          : 1;
  if (marker.circles.size() != expected_circles || marker.keypoints.size() < 2) {
    if (error) *error = std::string("malformed ") + ToString(marker.kind) + " marker";
    return std::nullopt;
  }
  // Paper frame: origin at m0, +X along m0 -> m1, same plane normal (a rotation about z).
  const Eigen::Vector2d m0 = marker.keypoints[0];
  const Eigen::Vector2d axis = marker.keypoints[1] - m0;
  geometry.Lx = axis.norm();
  if (!(geometry.Lx > 0.0)) {
    if (error) *error = "m0 and m1 coincide";
    return std::nullopt;
  }
  const Eigen::Vector2d x = axis / geometry.Lx;
  Eigen::Matrix2d marker_from_paper_2d;
  marker_from_paper_2d << x.x(), -x.y(), x.y(), x.x();
  geometry.marker_from_paper.rotation.topLeftCorner<2, 2>() = marker_from_paper_2d;
  geometry.marker_from_paper.translation << m0, 0.0;
  for (size_t i = 0; i < marker.circles.size(); ++i) {
    const Eigen::Vector2d center =
        marker_from_paper_2d.transpose() * (marker.circles[i].center - m0);
    geometry.centers.push_back(center);
    geometry.radii_m.push_back(marker.circles[i].radius_m);
    const double tolerance = 1e-9 * geometry.Lx;
    if (i > 0 && (center - Eigen::Vector2d(geometry.Lx, 0.0)).norm() <= tolerance) {
      geometry.m1_circle = static_cast<int>(i);
    }
  }
  if (geometry.centers[0].norm() > 1e-9 * geometry.Lx) {
    if (error) *error = "the first circle must be centred at m0";
    return std::nullopt;
  }
  return geometry;
}

std::vector<Eigen::Matrix3d> ConicsImagedThrough(const CircleGeometry& geometry,
                                                 const Eigen::Matrix3d& H) {
  std::vector<Eigen::Matrix3d> conics_px;
  for (size_t i = 0; i < geometry.centers.size(); ++i) {
    conics_px.push_back(
        CanonicalConic(ImageOfCircle<double>(H, geometry.centers[i], geometry.radii_m[i])));
  }
  return conics_px;
}

Rigid3 OtherTilt(const Rigid3& cam_from_plane) {
  const Eigen::Vector3d ray = cam_from_plane.translation.normalized();
  const Eigen::Matrix3d reflect_about_ray =
      2.0 * ray * ray.transpose() - Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d half_turn = Eigen::Vector3d(-1.0, -1.0, 1.0).asDiagonal();
  return {reflect_about_ray * cam_from_plane.rotation * half_turn, cam_from_plane.translation};
}

}  // namespace markerbench
