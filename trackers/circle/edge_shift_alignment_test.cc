// Tracking mode's coarse step (edge_shift_alignment.h) on rendered frames with known poses: a
// prediction a degree and 5 mm off (15.5 px in the image) moved onto the circles' edges, for
// every disk marker, sharp and blurred, at low and heavy noise, and the circle's other tilt fitted
// to the same edges; no move where the marker is not there or lies beyond the rays' reach.
#include "trackers/circle/edge_shift_alignment.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "core/marker_yaml.h"
#include "renderer/render_frame.h"
#include "renderer/test_scenes.h"
#include "testing/square_tracker_testing.h"
#include "trackers/circle/conic.h"
#include "trackers/circle/pixel_fit.h"

namespace markerbench {
namespace {

MarkerSpec Load(const std::string& kind) {
  return LoadMarkerYaml("scenarios/markers/" + kind + ".yaml");
}

// The farthest any circle's image lies from its image at `truth`: the larger of the ellipses'
// centres' distance and their semi-axes' differences (px).
double FarthestEllipsePx(const CircleGeometry& geometry,
                         const Camera& camera,
                         const Rigid3& cam_from_paper,
                         const Rigid3& truth) {
  const auto conics = [&](const Rigid3& pose) {
    return ConicsImagedThrough(geometry, camera.K() * RayFromPlane(pose));
  };
  const std::vector<Eigen::Matrix3d> at = conics(cam_from_paper), at_truth = conics(truth);
  double farthest = 0.0;
  for (size_t i = 0; i < at.size(); ++i) {
    const Ellipse a = EllipseFromConic(at[i]), b = EllipseFromConic(at_truth[i]);
    farthest = std::max({farthest,
                         (a.center - b.center).norm(),
                         std::abs(a.semi_major - b.semi_major),
                         std::abs(a.semi_minor - b.semi_minor)});
  }
  return farthest;
}

struct Aligning {
  MarkerSpec marker;
  CircleGeometry geometry;
  std::vector<CircleDetector::EdgeClearance> clearances;
  Camera camera = FrameRequest().scene.camera;  // RenderMarker's
  explicit Aligning(const std::string& kind)
      : marker(Load(kind)), geometry(*CircleGeometryOf(marker, nullptr)) {
    const CircleDetector detector(marker, geometry, {});
    for (size_t i = 0; i < geometry.radii_m.size(); ++i) {
      clearances.push_back(detector.ClearanceOf(i));
    }
  }
  std::optional<EdgeShiftAlignment> Align(const RenderedFrame& frame,
                                          const Rigid3& predicted_cam_from_paper,
                                          double blur_sigma_px,
                                          std::string* why) const {
    const Eigen::VectorXd levels = UnitGainLevels(7 + 2 * frame.image.channels);
    return AlignByEdgeShifts(frame.image,
                             camera,
                             marker,
                             geometry,
                             clearances,
                             predicted_cam_from_paper,
                             levels,
                             std::max(0.5, blur_sigma_px),
                             {},
                             why);
  }
};

// The truth turned by a degree about an axis in the image plane and moved 5 mm across.
Rigid3 OffByADegree(const Rigid3& cam_from_paper, double axis_angle_rad) {
  const Eigen::Vector3d axis(std::cos(axis_angle_rad), std::sin(axis_angle_rad), 0.0);
  const Rigid3 turn(RotationFromVector(M_PI / 180.0 * axis),
                    0.005 * axis.cross(Eigen::Vector3d::UnitZ()));
  return turn * cam_from_paper;
}

// At σ² 0.02, sharp and blurred by 2 px, every disk marker's prediction (its ellipses 15.5 px
// off) is moved onto the truth's ellipses to within half a pixel (measured: at most 0.20 px). At
// σ² 0.3 (a pixel's noise σ 0.55 against a contrast of 1) a single ray's edge is good to about a
// pixel: a and d, whose edges have room each side, are moved to within a pixel (measured: at most
// 0.80 and 0.48 px); b's and c's inner ink (b's feature dot, c's inner circle) leaves their rays
// less room, and there the alignment may decline (measured: on 5 and 4 of 8 frames), but where it
// moves a prediction, it is to within a pixel too (0.28 and 0.33 px).
TEST(EdgeShiftAlignment, MovesAPredictionADegreeOffOntoTheEdges) {
  for (const char* kind : {"circles_a", "circles_b", "circles_c", "circle_d"}) {
    const Aligning aligning(kind);
    const bool room_each_side = std::string(kind) == "circles_a" || std::string(kind) == "circle_d";
    const bool single_circle = std::string(kind) == "circle_d";
    const bool two_disks = std::string(kind) == "circles_a" || std::string(kind) == "circles_b";
    for (const double blur : {0.0, 2.0}) {
      for (const double noise_var : {0.02, 0.3}) {
        for (int pose = 0; pose < 4; ++pose) {
          SCOPED_TRACE(std::string(kind) + " blur " + std::to_string(blur) + " noise " +
                       std::to_string(noise_var) + " pose " + std::to_string(pose));
          const Rigid3 cam_from_marker = TiltedView(0.6, 10.0 + 10.0 * pose, 30.0 + 70.0 * pose);
          const Rigid3 truth = cam_from_marker * aligning.geometry.marker_from_paper;
          const RenderedFrame frame =
              RenderMarker(aligning.marker, cam_from_marker, noise_var, blur, 100 + pose);
          const Rigid3 predicted = OffByADegree(truth, 0.8 * pose);
          ASSERT_GT(FarthestEllipsePx(aligning.geometry, aligning.camera, predicted, truth), 10.0);
          std::string why;
          const std::optional<EdgeShiftAlignment> aligned =
              aligning.Align(frame, predicted, blur, &why);
          const bool heavy_noise = noise_var > 0.1;
          if (!aligned) {
            EXPECT_TRUE(heavy_noise && !room_each_side) << why;
            continue;
          }
          EXPECT_LE(
              FarthestEllipsePx(aligning.geometry, aligning.camera, aligned->cam_from_paper, truth),
              heavy_noise ? 1.0 : 0.5);
          // The circle's other tilt: d's single circle fits it as well (its two tilts give one
          // ellipse; measured within 3 %); a's and b's two disks rule it out, 2 ln Λ =
          // N (rms_other² / rms² - 1) of 130 or more at σ² 0.02 (CircleTracker asks for 100).
          if (single_circle) {
            EXPECT_NEAR(aligned->other_tilt_rms_px, aligned->rms_px, 0.1 * aligned->rms_px);
          } else if (two_disks && !heavy_noise) {
            const double ratio = aligned->other_tilt_rms_px / aligned->rms_px;
            EXPECT_GE(aligned->points_kept * (ratio * ratio - 1.0), 120.0);
          }
        }
      }
    }
  }
}

TEST(EdgeShiftAlignment, DoesNotMoveWhereTheEdgesDoNotShow) {
  const Aligning aligning("circles_a");
  const Rigid3 cam_from_marker = TiltedView(0.6, 25.0, 40.0);
  const Rigid3 truth = cam_from_marker * aligning.geometry.marker_from_paper;
  std::string why;
  // Blank paper.
  MarkerSpec blank = aligning.marker;
  blank.layers.clear();
  const RenderedFrame empty = RenderMarker(blank, cam_from_marker, 0.02, 0.0, 7);
  EXPECT_FALSE(aligning.Align(empty, truth, 0.5, &why));
  EXPECT_NE(why.find("rays"), std::string::npos) << why;
  // A prediction 5 cm off (about 70 px): beyond the rays' reach.
  const RenderedFrame frame = RenderMarker(aligning.marker, cam_from_marker, 0.02, 0.0, 8);
  Rigid3 far = truth;
  far.translation.x() += 0.05;
  EXPECT_FALSE(aligning.Align(frame, far, 0.5, &why));
  // Levels of a grey image (one channel) for an RGB frame: declined, never read past their end.
  EXPECT_FALSE(AlignByEdgeShifts(frame.image,
                                 aligning.camera,
                                 aligning.marker,
                                 aligning.geometry,
                                 aligning.clearances,
                                 truth,
                                 UnitGainLevels(7 + 2),
                                 0.5,
                                 {},
                                 &why));
  EXPECT_NE(why.find("channels"), std::string::npos) << why;
}

}  // namespace
}  // namespace markerbench
