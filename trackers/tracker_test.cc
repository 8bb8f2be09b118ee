#include "trackers/tracker.h"

#include <gtest/gtest.h>

#include "core/marker_yaml.h"
#include "trackers/tracker_factory.h"

namespace markerbench {
namespace {

TEST(TrackStatus, NamesRoundTrip) {
  for (TrackStatus s : {TrackStatus::kOk,
                        TrackStatus::kNotDetected,
                        TrackStatus::kWrongId,
                        TrackStatus::kPoseFailed,
                        TrackStatus::kError}) {
    EXPECT_EQ(TrackStatusFromString(ToString(s)), s);
  }
  EXPECT_STREQ(ToString(TrackStatus::kNotDetected), "not_detected");
  EXPECT_FALSE(TrackStatusFromString("lost").has_value());
}

// Each library tracker takes exactly its own marker kind and family, as the harness pairs
// trackers with markers by CanTrack.
TEST(TrackerFactory, TrackersCanTrackTheirOwnMarkersOnly) {
  const MarkerSpec apriltag = LoadMarkerYaml("scenarios/markers/apriltag.yaml");
  const MarkerSpec aruco = LoadMarkerYaml("scenarios/markers/aruco.yaml");
  const MarkerSpec circles = LoadMarkerYaml("scenarios/markers/circles_a.yaml");
  MarkerSpec other_family = apriltag;
  other_family.family = "tag25h9";
  for (const std::string& name : TrackerNames()) {
    const auto tracker = MakeTracker(name, nullptr);
    const bool is_aruco = name == "aruco";
    EXPECT_EQ(tracker->CanTrack(apriltag), !is_aruco) << name;
    EXPECT_EQ(tracker->CanTrack(aruco), is_aruco) << name;
    EXPECT_FALSE(tracker->CanTrack(circles)) << name;
    EXPECT_FALSE(tracker->CanTrack(other_family)) << name;
  }
}

}  // namespace
}  // namespace markerbench
