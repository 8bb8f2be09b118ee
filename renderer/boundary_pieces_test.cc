#include "renderer/boundary_pieces.h"

#include <gtest/gtest.h>

#include <cmath>

#include "renderer/test_scenes.h"

namespace markerbench {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kLengthTol = 1e-3;  // relative: chords of 0.25 px on circles of 30+ px

const Eigen::AlignedBox2d kWholeImage(Eigen::Vector2d(-0.5, -0.5), Eigen::Vector2d(639.5, 479.5));

Scene FaceOn(const MarkerSpec& marker) {
  Scene scene;
  scene.marker = &marker;
  scene.cam_from_marker = TiltedView(1.0, 0.0, 0.0);
  return scene;
}

double TotalLengthPx(const std::vector<BoundaryPiece>& pieces) {
  double length = 0.0;
  for (const BoundaryPiece& p : pieces) length += (p.b_px - p.a_px).norm();
  return length;
}

TEST(BoundaryPiecesTest, ADiskOnPaperIsOneCircleWithTheJumpOutwards) {
  const MarkerSpec disk = BlackDiskMarker(0.05);  // 30 px at 1 m, f = 600
  const std::vector<BoundaryPiece> pieces = ImageBoundaryPieces(FaceOn(disk), 1, kWholeImage, 0.25);
  EXPECT_NEAR(TotalLengthPx(pieces), 2.0 * kPi * 30.0, kLengthTol * 2.0 * kPi * 30.0);
  const Eigen::Vector2d center(319.5, 239.5);
  for (const BoundaryPiece& p : pieces) {
    ASSERT_LE((p.b_px - p.a_px).norm(), 0.25);
    EXPECT_DOUBLE_EQ(p.jump[0], 1.0);  // white outside minus black inside
    EXPECT_GT(p.normal_px.dot(0.5 * (p.a_px + p.b_px) - center), 0.0);  // towards the paper
  }
}

TEST(BoundaryPiecesTest, HiddenAndSharedEdgesCountOnce) {
  MarkerSpec marker = BlackDiskMarker(0.05);
  // The same disk again on top (shared edge), and a small black disk inside it (hidden).
  marker.layers.push_back(marker.layers.front());
  const PaintedShape hidden{DiskShape{Eigen::Vector2d(0.01, 0.0), 0.02}, Rgb::Zero()};
  marker.layers.push_back(hidden);
  const std::vector<BoundaryPiece> pieces =
      ImageBoundaryPieces(FaceOn(marker), 1, kWholeImage, 0.25);
  EXPECT_NEAR(TotalLengthPx(pieces), 2.0 * kPi * 30.0, kLengthTol * 2.0 * kPi * 30.0);
}

TEST(BoundaryPiecesTest, AGridKeepsOnlyTheEdgesBetweenInkAndPaper) {
  // Two ink cells side by side in a 1 x 2 grid: the outline of a 2 x 1 rectangle.
  MarkerSpec marker = BlackSquareMarker(-0.05, -0.025, 0.05);
  auto& grid = std::get<GridShape>(marker.layers.front().shape);
  grid.cols = 2;
  grid.ink = {1, 1};
  const std::vector<BoundaryPiece> pieces =
      ImageBoundaryPieces(FaceOn(marker), 3, kWholeImage, 0.25);
  EXPECT_NEAR(TotalLengthPx(pieces), 2.0 * (60.0 + 30.0), kLengthTol * 180.0);
  const Eigen::Vector2d center(319.5, 239.5);  // the rectangle is centred on the axis
  for (const BoundaryPiece& p : pieces) {
    for (const double jump : p.jump) EXPECT_DOUBLE_EQ(std::abs(jump), 1.0);
    // The paper (the brighter side) lies outside the rectangle.
    EXPECT_GT(p.jump[0] * p.normal_px.dot(0.5 * (p.a_px + p.b_px) - center), 0.0);
  }
}

TEST(BoundaryPiecesTest, ALowerLayerShowingThroughMakesAnEdgeOfAnUpperOne) {
  // A white 0.1 m cell over the corner of a black disk of radius 5 cm: the cell's top side
  // (y = 2 cm) is an edge only where the disk lies above it, x in [0, sqrt(5² - 2²) cm], and
  // its midpoint (x = 5 cm) is not there.
  MarkerSpec marker = BlackDiskMarker(0.05);
  MarkerSpec cell = BlackSquareMarker(0.0, -0.08, 0.1);
  std::get<GridShape>(cell.layers.front().shape).ink = {0};
  marker.layers.push_back(cell.layers.front());
  const std::vector<BoundaryPiece> pieces =
      ImageBoundaryPieces(FaceOn(marker), 1, kWholeImage, 0.25);
  const double top_row_px = 239.5 - 600.0 * 0.02;
  double top_side_px = 0.0;
  for (const BoundaryPiece& p : pieces) {
    if (std::abs(p.a_px.y() - top_row_px) < 1e-6 && std::abs(p.b_px.y() - top_row_px) < 1e-6) {
      top_side_px += (p.b_px - p.a_px).norm();
    }
  }
  const double expected_px = 600.0 * std::sqrt(0.05 * 0.05 - 0.02 * 0.02);
  EXPECT_NEAR(top_side_px, expected_px, 0.25);  // one piece at the disk's crossing
}

TEST(BoundaryPiecesTest, KeepsOnlyPiecesInTheWindow) {
  const MarkerSpec disk = BlackDiskMarker(0.05);
  const Eigen::AlignedBox2d left_half(Eigen::Vector2d(-0.5, -0.5), Eigen::Vector2d(319.5, 479.5));
  const std::vector<BoundaryPiece> pieces = ImageBoundaryPieces(FaceOn(disk), 1, left_half, 0.25);
  EXPECT_NEAR(TotalLengthPx(pieces), kPi * 30.0, 0.01 * kPi * 30.0);
  for (const BoundaryPiece& p : pieces) {
    EXPECT_TRUE(left_half.contains(p.a_px) || left_half.contains(p.b_px));
  }
}

TEST(BoundaryPiecesTest, ProjectionJacobianMatchesFiniteDifferences) {
  Camera camera;
  camera.distortion = {-0.2, 0.05, 0.001, -0.002, 0.01};
  const Eigen::Vector3d x_cam(0.1, -0.07, 0.5);
  const Eigen::Matrix<double, 2, 3> J = ImgFromCamJacobian(camera, x_cam);
  constexpr double kStep = 1e-7;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d d = kStep * Eigen::Vector3d::Unit(k);
    const Eigen::Vector2d numeric =
        (camera.ImgFromCam(x_cam + d) - camera.ImgFromCam(x_cam - d)) / (2.0 * kStep);
    EXPECT_NEAR((J.col(k) - numeric).norm(), 0.0, 1e-5 * numeric.norm() + 1e-6) << k;
  }
}

}  // namespace
}  // namespace markerbench
