// The roll and centre of markers e and f from the design inside their circle, on rendered
// frames with known poses.
#include "trackers/circle/roll_feature.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <tuple>

#include "core/gamma_curve.h"
#include "core/marker_yaml.h"
#include "renderer/test_scenes.h"
#include "testing/square_tracker_testing.h"

namespace markerbench {
namespace {

MarkerSpec Load(const std::string& kind) {
  return LoadMarkerYaml("scenarios/markers/" + kind + ".yaml");
}

// The design's first moment points along its axis of symmetry: e's mouth's bisector (-45°),
// f's wedge's (30°), as the shapes are drawn.
TEST(RollFeature, DesignMomentLiesOnTheAxisOfSymmetry) {
  for (const auto& [kind, axis_deg] : {std::pair<const char*, double>{"circle_e", -45.0},
                                       std::pair<const char*, double>{"circle_f", 30.0}}) {
    const MarkerSpec marker = Load(kind);
    const RollFeature feature(marker, *CircleGeometryOf(marker, nullptr));
    const Eigen::Vector2d m = feature.design_moment();
    EXPECT_NEAR(std::atan2(m.y(), m.x()) * 180.0 / M_PI, axis_deg, 0.01) << kind;
  }
}

// From a pose turned 0.2 rad off about the circle's axis (and right otherwise), on noise-free
// frames: the turn back and the centre, and the design shows at its printed contrast. f
// within 0.05° and 0.05 mm; e within 0.15° and 0.1 mm (measured 0.10° and 0.053 mm at 1 m
// and 40°, where the mouth is 3 px wide and its arcs' curvature, left out, tells).
TEST(RollFeature, FindsTheRollAndCentre) {
  for (const auto& [kind, turn_deg, center_m] :
       {std::tuple<const char*, double, double>{"circle_e", 0.15, 1e-4},
        std::tuple<const char*, double, double>{"circle_f", 0.05, 5e-5}}) {
    const MarkerSpec marker = Load(kind);
    const CircleGeometry geometry = *CircleGeometryOf(marker, nullptr);
    const RollFeature feature(marker, geometry);
    int frames = 0;
    for (double distance : {0.6, 1.0}) {
      for (double tilt : {0.0, 20.0, 40.0}) {
        for (double roll : {10.0, 130.0, 250.0}) {
          SCOPED_TRACE(std::string(kind) + " d=" + std::to_string(distance) +
                       " tilt=" + std::to_string(tilt) + " roll=" + std::to_string(roll));
          const Rigid3 truth = TiltedView(distance, tilt, roll);
          const FrameRequest request = SeededFrameRequest(marker, truth, 0.0, 1.0, ++frames, 1);
          const RenderedFrame frame = RenderFrame(request);
          Rigid3 start = truth;
          start.rotation = truth.rotation * Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitZ());
          const std::optional<RollAlignment> fit =
              feature.Align(frame.image, request.scene.camera, start, 255.0, 1.1, 0.3, true);
          ASSERT_TRUE(fit);
          EXPECT_NEAR(fit->turn_rad * 180.0 / M_PI, -0.2 * 180.0 / M_PI, turn_deg);
          EXPECT_LE(fit->center_m.norm(), center_m);
          EXPECT_TRUE(fit->shows_design);
          EXPECT_NEAR(fit->contrast_ratio, 1.0, 0.1);
        }
      }
    }
  }
}

// A disk without the design (circle_d's disk and dots, read as e or f) does not show it.
TEST(RollFeature, ADiskWithoutTheDesignDoesNotShowIt) {
  const MarkerSpec d = Load("circle_d");
  for (const char* kind : {"circle_e", "circle_f"}) {
    const MarkerSpec marker = Load(kind);
    const RollFeature feature(marker, *CircleGeometryOf(marker, nullptr));
    for (double noise_var : {0.0, 0.02}) {
      const Rigid3 truth = TiltedView(0.6, 25.0, 40.0);
      const FrameRequest request = SeededFrameRequest(d, truth, noise_var, 1.0, 5, 1);
      const RenderedFrame frame = RenderFrame(request);
      const double noise = 255.0 * std::sqrt(noise_var);
      const std::optional<RollAlignment> fit =
          feature.Align(frame.image, request.scene.camera, truth, 255.0, 1.1, noise, true);
      EXPECT_FALSE(fit && fit->shows_design) << kind << " " << noise_var;
    }
  }
}

// A camera's response or a print moves f's grey wedge between the disk's level and the paper's:
// the wedge shows at its level (0.5^(1/2.2) = 0.73 encoded with gamma 2.2, 0.4 printed at 0.4),
// and a wedge at 0.26, nearer the disk than kMinIntermediateLevel (clutter on a dark disk), does
// not show (below about 0.25 its moment is too weak to be read at all).
TEST(RollFeature, ReadsFsWedgeAtTheLevelItShows) {
  const MarkerSpec f = Load("circle_f");
  const RollFeature feature(f, *CircleGeometryOf(f, nullptr));
  struct Printing {
    double grey, gamma, level;
    bool shows;
  };
  for (const Printing& printing : {Printing{0.5, 2.2, std::pow(0.5, 1.0 / 2.2), true},
                                   Printing{0.4, 1.0, 0.4, true},
                                   Printing{0.26, 1.0, 0.26, false}}) {
    SCOPED_TRACE("grey " + std::to_string(printing.grey) + ", gamma " +
                 std::to_string(printing.gamma));
    MarkerSpec printed = f;
    printed.layers.back().color = Rgb::Constant(printing.grey);
    const Rigid3 truth = TiltedView(0.6, 25.0, 40.0);
    const FrameRequest request = SeededFrameRequest(printed, truth, 1e-4, 1.0, 5, 1);
    Image8 image = RenderFrame(request).image;
    ApplyGammaCurve(1.0 / printing.gamma, &image);
    const std::optional<RollAlignment> fit =
        feature.Align(image, request.scene.camera, truth, 255.0, 1.1, 2.55, true);
    ASSERT_TRUE(fit);
    EXPECT_NEAR(fit->design_level, printing.level, 0.02);
    EXPECT_EQ(fit->shows_design, printing.shows) << fit->misfit;
  }
}

// The level is PrintedLevel's (from the design's darkest luma to its lightest), as the bounds on
// it are: f printed inverted, a white disk on black paper, shows its grey wedge under gamma 2.2
// at 0.73 as the upright one does (from the disk to the paper that is 0.27, below the bounds).
TEST(RollFeature, ReadsTheWedgeOfAnInvertedFAtItsLevelFromTheDarkest) {
  MarkerSpec inverted = Load("circle_f");
  inverted.background = Rgb::Zero();
  inverted.circles[0].color = inverted.layers[0].color = Rgb::Ones();
  const RollFeature feature(inverted, *CircleGeometryOf(inverted, nullptr));
  const Rigid3 truth = TiltedView(0.6, 25.0, 40.0);
  const FrameRequest request = SeededFrameRequest(inverted, truth, 1e-4, 1.0, 5, 1);
  Image8 image = RenderFrame(request).image;
  ApplyGammaCurve(1.0 / 2.2, &image);
  const std::optional<RollAlignment> fit =
      feature.Align(image, request.scene.camera, truth, 0.0, 1.1, 2.55, true);
  ASSERT_TRUE(fit);
  EXPECT_NEAR(fit->design_level, std::pow(0.5, 1.0 / 2.2), 0.02);
  EXPECT_TRUE(fit->shows_design) << fit->misfit;
}

}  // namespace
}  // namespace markerbench
