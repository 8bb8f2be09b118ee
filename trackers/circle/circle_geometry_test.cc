// The circle markers' geometry: their circles imaged through a pose, against the points of
// each circle projected one by one.
#include "trackers/circle/circle_geometry.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "core/marker_yaml.h"
#include "renderer/render_frame.h"
#include "trackers/circle/conic.h"

namespace markerbench {
namespace {

CircleGeometry GeometryOf(const std::string& kind) {
  return *CircleGeometryOf(LoadMarkerYaml("scenarios/markers/" + kind + ".yaml"), nullptr);
}

TEST(ConicsImagedThrough, EachCirclesPointsLieOnItsConicAndItsCentreInside) {
  const Camera camera = FrameRequest().scene.camera;
  Rigid3 cam_from_paper;
  cam_from_paper.rotation =
      Eigen::AngleAxisd(2.6, Eigen::Vector3d(0.3, 0.9, 0.2).normalized()).toRotationMatrix();
  cam_from_paper.translation = Eigen::Vector3d(0.03, -0.02, 0.7);
  for (const std::string kind : {"circles_a", "circles_c", "circle_d"}) {
    SCOPED_TRACE(kind);
    const CircleGeometry geometry = GeometryOf(kind);
    const Eigen::Matrix3d H = camera.K() * RayFromPlane(cam_from_paper);
    const std::vector<Eigen::Matrix3d> conics = ConicsImagedThrough(geometry, H);
    ASSERT_EQ(conics.size(), geometry.centers.size());
    for (size_t i = 0; i < conics.size(); ++i) {
      EXPECT_NEAR(conics[i].norm(), 1.0, 1e-12);  // canonical scale
      // The points of circle i, projected one by one: on the conic to rounding, its distance
      // xᵀCx / |∇(xᵀCx)| (px) within 1e-9 px.
      for (int k = 0; k < 12; ++k) {
        const double angle = 2.0 * M_PI * k / 12;
        const Eigen::Vector2d on_plane =
            geometry.centers[i] +
            geometry.radii_m[i] * Eigen::Vector2d(std::cos(angle), std::sin(angle));
        const Eigen::Vector3d x = (H * on_plane.homogeneous()).hnormalized().homogeneous();
        const double gradient = 2.0 * (conics[i] * x).head<2>().norm();
        EXPECT_NEAR(x.dot(conics[i] * x) / gradient, 0.0, 1e-9) << "circle " << i << ", " << k;
      }
      // The centre's image lies inside: negative, the canonical sign.
      const Eigen::Vector3d centre =
          (H * geometry.centers[i].homogeneous()).hnormalized().homogeneous();
      EXPECT_LT(centre.dot(conics[i] * centre), 0.0) << "circle " << i;
    }
  }
}

TEST(ConicsImagedThrough, AFrontoParallelCircleImagesAsACircleScaledByFocalOverDepth) {
  const Camera camera = FrameRequest().scene.camera;
  const CircleGeometry geometry = GeometryOf("circles_a");
  Rigid3 cam_from_paper;
  cam_from_paper.translation = Eigen::Vector3d(0.01, -0.02, 0.8);
  const std::vector<Eigen::Matrix3d> conics =
      ConicsImagedThrough(geometry, camera.K() * RayFromPlane(cam_from_paper));
  const Eigen::Matrix3d K = camera.K();
  for (size_t i = 0; i < conics.size(); ++i) {
    const Ellipse e = EllipseFromConic(conics[i]);
    const Eigen::Vector3d on_camera =
        cam_from_paper * Eigen::Vector3d(geometry.centers[i].x(), geometry.centers[i].y(), 0.0);
    EXPECT_NEAR((e.center - (K * on_camera).hnormalized()).norm(), 0.0, 1e-9) << i;
    EXPECT_NEAR(e.semi_major, K(0, 0) * geometry.radii_m[i] / 0.8, 1e-9) << i;
    EXPECT_NEAR(e.semi_minor, K(1, 1) * geometry.radii_m[i] / 0.8, 1e-9) << i;
  }
}

}  // namespace
}  // namespace markerbench
