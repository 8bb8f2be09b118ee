#include "core/marker_scaling.h"

#include <gtest/gtest.h>

#include "core/marker_yaml.h"

namespace markerbench {
namespace {

constexpr double kTol = 1e-12;

MarkerSpec Load(const std::string& name) {
  return LoadMarkerYaml("scenarios/markers/" + name + ".yaml");
}

TEST(MarkerScaling, EveryKindReachesTheTargetInkArea) {
  for (const char* name : {"circles_a",
                           "circles_b",
                           "circles_c",
                           "circle_d",
                           "circle_e",
                           "circle_f",
                           "apriltag",
                           "aruco",
                           "bit_grid",
                           "dot_rings"}) {
    const MarkerSpec marker = Load(name);
    const MarkerSpec scaled = ScaledMarker(marker, EqualAreaFactor(marker, 0.01));
    EXPECT_NEAR(scaled.InkBounds().volume(), 0.01, kTol) << name;
  }
}

TEST(MarkerScaling, ScalesEveryLengthAboutTheOrigin) {
  const MarkerSpec marker = Load("circle_e");
  const MarkerSpec scaled = ScaledMarker(marker, 2.0);
  ASSERT_EQ(scaled.circles.size(), marker.circles.size());
  EXPECT_EQ(scaled.circles[0].radius_m, 2.0 * marker.circles[0].radius_m);
  for (size_t k = 0; k < marker.keypoints.size(); ++k) {
    EXPECT_EQ(scaled.keypoints[k], 2.0 * marker.keypoints[k]);
  }
  EXPECT_TRUE(scaled.InkBounds().min().isApprox(2.0 * marker.InkBounds().min()));
  EXPECT_TRUE(scaled.InkBounds().max().isApprox(2.0 * marker.InkBounds().max()));
}

TEST(MarkerScaling, RoundTripsThroughTheInverseFactor) {
  for (const char* name : {"apriltag", "circle_f", "dot_rings"}) {
    const MarkerSpec marker = Load(name);
    const MarkerSpec back = ScaledMarker(ScaledMarker(marker, 1.7), 1.0 / 1.7);
    EXPECT_NEAR(back.size_m, marker.size_m, kTol) << name;
    EXPECT_TRUE(back.InkBounds().min().isApprox(marker.InkBounds().min(), kTol)) << name;
    EXPECT_TRUE(back.InkBounds().max().isApprox(marker.InkBounds().max(), kTol)) << name;
  }
}

}  // namespace
}  // namespace markerbench
