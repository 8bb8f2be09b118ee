#include "bench/plan/pose_sampler.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/number_text.h"

namespace markerbench {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

}  // namespace

LookAt DrawLookAt(const PoseSamplerOptions& o, Rng* rng) {
  LookAt a;
  a.distance_m = o.distance_m;
  a.tilt = rng->Uniform(o.tilt_min_deg, o.tilt_max_deg) * kDeg;
  a.azimuth = rng->Uniform(o.azimuth_min_deg, o.azimuth_max_deg) * kDeg;
  a.roll = rng->Uniform(o.roll_min_deg, o.roll_max_deg) * kDeg;
  a.offset_px = o.max_offset_px * std::sqrt(rng->Uniform());
  a.offset_angle = rng->Uniform(0.0, 360.0) * kDeg;
  return a;
}

Rigid3 LookAtPose(const LookAt& a, const Camera& camera) {
  const Eigen::Vector3d center_cam_pos =
      a.distance_m * Eigen::Vector3d(std::sin(a.tilt) * std::cos(a.azimuth),
                                     std::sin(a.tilt) * std::sin(a.azimuth),
                                     std::cos(a.tilt));
  // Camera axes in the marker frame: z towards the centre, x from a reference, then roll.
  const Eigen::Vector3d z = -center_cam_pos.normalized();
  const Eigen::Vector3d ref =
      std::abs(z.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d x0 = (ref - ref.dot(z) * z).normalized();
  const Eigen::Vector3d y0 = z.cross(x0);
  const Eigen::Vector3d x = std::cos(a.roll) * x0 + std::sin(a.roll) * y0;
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Matrix3d center_from_cam;
  center_from_cam << x, y, z;
  Rigid3 cam_from_center(center_from_cam.transpose(),
                         -center_from_cam.transpose() * center_cam_pos);

  // Turn the camera so the centre's ray passes through the offset image point.
  const Eigen::Vector2d target(0.5 * (camera.width - 1) + a.offset_px * std::cos(a.offset_angle),
                               0.5 * (camera.height - 1) + a.offset_px * std::sin(a.offset_angle));
  const Eigen::Vector3d ray = camera.CamFromImg(target).normalized();
  const Eigen::Matrix3d turn =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), ray).toRotationMatrix();
  return Rigid3(turn, Eigen::Vector3d::Zero()) * cam_from_center;
}

Rigid3 CamFromMarker(const Rigid3& cam_from_center, const MarkerSpec& marker) {
  const Eigen::Vector2d c = marker.InkBounds().center();
  return cam_from_center * Rigid3(Eigen::Matrix3d::Identity(), -Eigen::Vector3d(c.x(), c.y(), 0));
}

bool MarkerFitsInImage(const MarkerSpec& marker,
                       const Camera& camera,
                       const Rigid3& cam_from_marker,
                       double border_px) {
  constexpr int kStepsPerSide = 8;  // distortion bends the sides
  for (const Eigen::Vector2d& p : BoxOutline(marker.InkBounds(), kStepsPerSide)) {
    const Eigen::Vector3d x_cam = cam_from_marker * Eigen::Vector3d(p.x(), p.y(), 0.0);
    if (!(x_cam.z() > 0.0)) return false;
    const Eigen::Vector2d px = camera.ImgFromCam(x_cam);
    if (!(px.x() >= border_px && px.y() >= border_px && px.x() <= camera.width - 1 - border_px &&
          px.y() <= camera.height - 1 - border_px)) {
      return false;
    }
  }
  return true;
}

bool MarkersFitInImage(const std::vector<MarkerSpec>& markers,
                       const Camera& camera,
                       const Rigid3& cam_from_center,
                       double border_px) {
  return std::all_of(markers.begin(), markers.end(), [&](const MarkerSpec& marker) {
    return MarkerFitsInImage(marker, camera, CamFromMarker(cam_from_center, marker), border_px);
  });
}

Rigid3 SamplePairedPose(const PoseSamplerOptions& options,
                        const Camera& camera,
                        const std::vector<MarkerSpec>& markers,
                        uint64_t seed) {
  Rng rng(seed);
  for (int draw = 0; draw < kMaxPoseDraws; ++draw) {
    const Rigid3 cam_from_center = SampleCamFromCenter(options, camera, &rng);
    if (MarkersFitInImage(markers, camera, cam_from_center, options.border_px)) {
      return cam_from_center;
    }
  }
  throw std::runtime_error("no pose in 1000 draws puts every marker inside the image at " +
                           NumberText(options.distance_m) +
                           " m; increase distance_m or reduce max_offset_px");
}

}  // namespace markerbench
