#include "core/camera.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

namespace markerbench {
namespace {

constexpr double kPixelRoundTripTol = 1e-9;  // Newton undistortion converges to ~1e-14

Camera DistortedCamera() {
  Camera camera;
  camera.distortion = {-0.28, 0.09, 0.0012, -0.0008, -0.015};  // a typical wide-ish lens
  return camera;
}

TEST(Camera, ProjectUnprojectRoundTripWithDistortion) {
  const Camera camera = DistortedCamera();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, camera.width - 1.0), v(0.0, camera.height - 1.0);
  for (int i = 0; i < 500; ++i) {
    const double y = v(rng);  // drawn before x: the order g++ gave them as arguments
    const Eigen::Vector2d px(u(rng), y);
    const Eigen::Vector3d ray = camera.CamFromImg(px);
    EXPECT_DOUBLE_EQ(ray.z(), 1.0);
    const Eigen::Vector2d back = camera.ImgFromCam(2.7 * ray);
    EXPECT_LE((back - px).norm(), kPixelRoundTripTol) << "pixel " << px.transpose();
  }
}

// Ideal pixels: the pinhole K's image of the ray through a pixel, and back through the lens.
TEST(Camera, IdealPixelsRoundTripWithDistortion) {
  const Camera camera = DistortedCamera();
  const Eigen::Matrix3d K = camera.K();
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(0.0, camera.width - 1.0), v(0.0, camera.height - 1.0);
  for (int i = 0; i < 500; ++i) {
    const double y = v(rng);
    const Eigen::Vector2d px(u(rng), y);
    const Eigen::Vector2d ideal = camera.IdealFromImg(px);
    const Eigen::Vector3d ray = camera.CamFromImg(px);
    EXPECT_LE((ideal - (K * ray).hnormalized()).norm(), 1e-12) << "pixel " << px.transpose();
    EXPECT_LE((camera.ImgFromIdeal(ideal) - px).norm(), kPixelRoundTripTol)
        << "pixel " << px.transpose();
  }
  // Barrel distortion: a pixel near the corner is an ideal pixel farther from the centre.
  const Eigen::Vector2d corner(5.0, 5.0), centre(camera.cx, camera.cy);
  EXPECT_GT((camera.IdealFromImg(corner) - centre).norm(), (corner - centre).norm() + 10.0);
}

TEST(Camera, IdealFromImgJacobianMatchesFiniteDifferences) {
  const Camera camera = DistortedCamera();
  constexpr double kStep = 1e-4;  // px
  for (const Eigen::Vector2d& px : {Eigen::Vector2d(320.0, 240.0),
                                    Eigen::Vector2d(20.0, 30.0),
                                    Eigen::Vector2d(610.5, 250.25)}) {
    const Eigen::Matrix2d analytic = camera.IdealFromImgJacobian(camera.CamFromImg(px));
    for (int c = 0; c < 2; ++c) {
      const Eigen::Vector2d step = Eigen::Vector2d::Unit(c) * kStep;
      const Eigen::Vector2d numeric =
          (camera.IdealFromImg(px + step) - camera.IdealFromImg(px - step)) / (2.0 * kStep);
      EXPECT_LE((analytic.col(c) - numeric).norm(), 1e-6) << "pixel " << px.transpose();
    }
  }
  // Near the corner the lens squeezes the image: a pixel there spans more than one ideal pixel.
  EXPECT_GT(camera.IdealFromImgJacobian(camera.CamFromImg({20.0, 30.0})).determinant(), 1.5);
}

TEST(Camera, PinholeAloneIgnoresTheLensAndRoundTrips) {
  const Camera camera = DistortedCamera();
  const Eigen::Matrix3d K = camera.K();
  for (const Eigen::Vector3d& x_cam : {Eigen::Vector3d(0.0, 0.0, 0.5),
                                       Eigen::Vector3d(-0.21, 0.13, 0.6),
                                       Eigen::Vector3d(0.9, -0.4, 2.5)}) {
    const Eigen::Vector2d ideal = camera.IdealFromCam(x_cam);
    EXPECT_LE((ideal - (K * x_cam).hnormalized()).norm(), 1e-12) << x_cam.transpose();
    const Eigen::Vector3d ray = camera.CamFromIdeal(ideal);
    EXPECT_EQ(ray.z(), 1.0);
    EXPECT_LE((ray - x_cam / x_cam.z()).norm(), 1e-15) << x_cam.transpose();
  }
  // Off the axis the lens moves the pixel; the pinhole does not.
  const Eigen::Vector3d off_axis(0.9, -0.4, 2.5);
  EXPECT_GT((camera.IdealFromCam(off_axis) - camera.ImgFromCam(off_axis)).norm(), 1.0);
}

TEST(Camera, IdealPixelsAreThePixelsWithoutDistortion) {
  const Camera camera;
  for (const Eigen::Vector2d& px : {Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(123.25, 407.5)}) {
    EXPECT_LE((camera.IdealFromImg(px) - px).norm(), 1e-12);
    EXPECT_LE((camera.ImgFromIdeal(px) - px).norm(), 1e-12);
  }
}

TEST(Camera, PrincipalPointProjectsOnAxis) {
  const Camera camera = DistortedCamera();
  const Eigen::Vector2d px = camera.ImgFromCam({0.0, 0.0, 1.0});
  EXPECT_DOUBLE_EQ(px.x(), camera.cx);
  EXPECT_DOUBLE_EQ(px.y(), camera.cy);
}

TEST(Camera, DistortJacobianMatchesFiniteDifferences) {
  const Camera camera = DistortedCamera();
  const Eigen::Vector2d n(0.31, -0.22);
  const Eigen::Matrix2d analytic = camera.DistortJacobian(n);
  constexpr double kStep = 1e-6;
  for (int c = 0; c < 2; ++c) {
    const Eigen::Vector2d step = Eigen::Vector2d::Unit(c) * kStep;
    const Eigen::Vector2d numeric =
        (camera.Distort(n + step) - camera.Distort(n - step)) / (2.0 * kStep);
    EXPECT_LE((analytic.col(c) - numeric).norm(), 1e-8);
  }
}

TEST(Camera, NoDistortionIsPinhole) {
  const Camera camera;
  const Eigen::Vector2d px = camera.ImgFromCam({0.1, -0.05, 2.0});
  EXPECT_DOUBLE_EQ(px.x(), 600.0 * 0.05 + 319.5);
  EXPECT_DOUBLE_EQ(px.y(), 600.0 * -0.025 + 239.5);
}

TEST(Camera, IsValidRejectsBadIntrinsics) {
  Camera camera;
  std::string error;
  EXPECT_TRUE(camera.IsValid(&error));
  camera.fx = -1.0;
  EXPECT_FALSE(camera.IsValid(&error));
  EXPECT_NE(error.find("fx=-1"), std::string::npos) << error;
}

}  // namespace
}  // namespace markerbench
