#include "trackers/circle/plane_view.h"

#include <Eigen/LU>
#include <cmath>

#include "core/shapes.h"

namespace markerbench {

PlaneView::PlaneView(const Camera& camera, const Rigid3& cam_from_plane)
    : camera_(camera),
      has_distortion_(camera.HasDistortion()),
      plane_from_ray_(RayFromPlane(cam_from_plane).inverse()),
      plane_from_px_(plane_from_ray_ * camera.K().inverse()) {}

PlaneLook PlaneView::Look(double x, double y) const {
  return LookAlong(camera_.CamFromImg(Eigen::Vector2d(x, y)));
}

PlaneLook PlaneView::LookAlong(const Eigen::Vector3d& ray) const {
  const Eigen::Vector3d q = plane_from_ray_ * ray;
  PlaneLook look;
  look.homogeneous = q.z();
  look.point = q.head<2>() / q.z();
  for (int j = 0; j < 2; ++j) {
    look.plane_from_px.col(j) =
        (plane_from_px_.block<2, 1>(0, j) - look.point * plane_from_px_(2, j)) / q.z();
  }
  if (has_distortion_) {
    const Eigen::Matrix2d ideal_from_px = camera_.IdealFromImgJacobian(ray);
    look.plane_from_px = look.plane_from_px * ideal_from_px;
    look.ideal_area_per_px = std::abs(ideal_from_px.determinant());
  }
  return look;
}

double LumaAt(const Image8& image, int x, int y) {
  const uint8_t* p = &image.pixels[(static_cast<size_t>(y) * image.width + x) * image.channels];
  return image.channels == 3 ? Luma(Rgb(p[0], p[1], p[2])) : p[0];
}

}  // namespace markerbench
