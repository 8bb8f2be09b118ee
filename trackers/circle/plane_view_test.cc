#include "trackers/circle/plane_view.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/camera_yaml.h"
#include "renderer/test_scenes.h"

namespace markerbench {
namespace {

// Through a wide lens (scenarios/cameras/wide_distorted.yaml), a pixel's local map to the plane
// and the plane's area it covers are the lens's: central differences of the plane points that
// neighbouring pixels see, near the image's centre and its sides.
TEST(PlaneView, LocalMapAndAreaFollowTheLens) {
  const Camera camera = LoadCameraYaml("scenarios/cameras/wide_distorted.yaml");
  const Rigid3 cam_from_plane = TiltedView(0.5, 30.0, 20.0);
  const PlaneView view(camera, cam_from_plane);
  const double ideal_pixel_area =
      std::abs(view.plane_from_ray().determinant()) / (camera.fx * camera.fy);
  constexpr double kStep = 1e-3;  // px
  for (const Eigen::Vector2d& px : {Eigen::Vector2d(320.0, 240.0),
                                    Eigen::Vector2d(25.0, 230.0),
                                    Eigen::Vector2d(615.0, 40.0)}) {
    const PlaneLook look = view.Look(px.x(), px.y());
    Eigen::Matrix2d numeric;
    for (int c = 0; c < 2; ++c) {
      const Eigen::Vector2d step = Eigen::Vector2d::Unit(c) * kStep;
      const Eigen::Vector2d ahead = px + step, behind = px - step;
      numeric.col(c) =
          (view.Look(ahead.x(), ahead.y()).point - view.Look(behind.x(), behind.y()).point) /
          (2.0 * kStep);
    }
    EXPECT_LE((look.plane_from_px - numeric).norm(), 1e-6 * numeric.norm())
        << "pixel " << px.transpose();
    const double h = look.homogeneous;
    EXPECT_NEAR(ideal_pixel_area * look.ideal_area_per_px / std::abs(h * h * h),
                std::abs(numeric.determinant()),
                1e-6 * std::abs(numeric.determinant()))
        << "pixel " << px.transpose();
  }
  // The lens squeezes the image towards its sides: there a pixel spans 2.3 ideal pixels, at its
  // corners 4.7 (computed apart, by Newton and finite differences in numpy).
  EXPECT_NEAR(view.Look(0.0, 240.0).ideal_area_per_px, 2.28, 0.01);
  EXPECT_NEAR(view.Look(0.0, 0.0).ideal_area_per_px, 4.71, 0.01);
}

TEST(PlaneView, PixelsAreIdealWithoutDistortion) {
  const Camera camera;
  const PlaneView view(camera, TiltedView(0.5, 30.0, 20.0));
  EXPECT_EQ(view.Look(10.0, 20.0).ideal_area_per_px, 1.0);
}

}  // namespace
}  // namespace markerbench
