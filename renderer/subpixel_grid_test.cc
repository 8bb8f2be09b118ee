#include "renderer/subpixel_grid.h"

#include <gtest/gtest.h>

namespace markerbench {
namespace {

constexpr double kRoundTripTol = 1e-9;  // px; double arithmetic on coordinates below 1e4

Camera DistortedCamera() {
  Camera camera;
  camera.distortion = {-0.2, 0.05, 0.001, -0.002, 0.0};
  return camera;
}

TEST(SubpixelGrid, TheFineCameraSeesEachPointAtItsSubpixelCoordinates) {
  const Camera canvas = DistortedCamera();
  const SubpixelGrid grid{5, {-7, 12, 300, 200}};
  const Camera fine = grid.FineCamera(canvas);
  EXPECT_EQ(fine.width, 5 * 307);
  EXPECT_EQ(fine.height, 5 * 188);
  for (const Eigen::Vector3d& x_cam : {Eigen::Vector3d(0.1, -0.05, 1.0),
                                       Eigen::Vector3d(-0.3, 0.2, 0.8),
                                       Eigen::Vector3d(0.0, 0.0, 2.0)}) {
    const Eigen::Vector2d expected =
        grid.FineFromCanvas(canvas.ImgFromCam(x_cam)) - 5.0 * Eigen::Vector2d(-7, 12);
    EXPECT_LE((fine.ImgFromCam(x_cam) - expected).norm(), kRoundTripTol);
    // And back: the fine camera's ray through the point's sub-pixel is the point's ray.
    const Eigen::Vector3d ray = fine.CamFromImg(fine.ImgFromCam(x_cam));
    EXPECT_LE((ray - x_cam / x_cam.z()).norm(), kRoundTripTol);
  }
}

TEST(SubpixelGrid, SubpixelsTileTheirPixel) {
  const SubpixelGrid grid{4, {10, 20, 30, 40}};
  // Canvas pixel u spans [u - ½, u + ½], sub-pixels 4u to 4u + 3: the edges 4u - ½, 4u + 3.5.
  EXPECT_EQ(grid.FineFromCanvas({9.5, 19.5}), Eigen::Vector2d(39.5, 79.5));
  EXPECT_EQ(grid.FineFromCanvas({10.5, 20.5}), Eigen::Vector2d(43.5, 83.5));
  EXPECT_EQ(grid.FineFromCanvas({10.0, 20.0}), Eigen::Vector2d(41.5, 81.5));  // centre of 40..43
  // Row j of the grid's image is sub-pixel row 80 + j; its centre in canvas rows, and back.
  for (int j : {0, 3, 4, 17}) {
    const double canvas_row = grid.CanvasRow(j);
    EXPECT_NEAR(grid.FineFromCanvas({0.0, canvas_row}).y() - 80.0, j, kRoundTripTol) << j;
  }
  EXPECT_DOUBLE_EQ(grid.CanvasRow(0), 19.625);
}

TEST(SubpixelGrid, ScaleOneIsTheCanvasExactly) {
  const Camera canvas = DistortedCamera();
  const SubpixelGrid grid{1, {0, 0, canvas.width, canvas.height}};
  const Camera same = grid.FineCamera(canvas);
  EXPECT_EQ(same.cx, canvas.cx);
  EXPECT_EQ(same.cy, canvas.cy);
  EXPECT_EQ(same.fx, canvas.fx);
  EXPECT_EQ(grid.FineFromCanvas({123.456, 7.891}), Eigen::Vector2d(123.456, 7.891));
  EXPECT_EQ(grid.CanvasRow(37.5), 37.5);
}

}  // namespace
}  // namespace markerbench
