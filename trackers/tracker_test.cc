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

// Each tracker takes exactly its own marker kinds and family, as the harness pairs trackers
// with markers by CanTrack.
TEST(TrackerFactory, TrackersCanTrackTheirOwnMarkersOnly) {
  const MarkerSpec apriltag = LoadMarkerYaml("scenarios/markers/apriltag.yaml");
  const MarkerSpec aruco = LoadMarkerYaml("scenarios/markers/aruco.yaml");
  const MarkerSpec artkplus = LoadMarkerYaml("scenarios/markers/artkplus.yaml");
  const MarkerSpec runetag = LoadMarkerYaml("scenarios/markers/runetag.yaml");
  MarkerSpec other_family = apriltag;
  other_family.family = "tag25h9";
  for (const std::string& name : TrackerNames()) {
    const auto tracker = MakeTracker(name, nullptr);
    const bool is_aruco = name == "aruco", is_circle = name == "circle";
    const bool is_artkplus = name == "artkplus", is_runetag = name == "runetag";
    EXPECT_EQ(tracker->CanTrack(apriltag), !is_aruco && !is_circle && !is_artkplus && !is_runetag)
        << name;
    EXPECT_EQ(tracker->CanTrack(aruco), is_aruco) << name;
    EXPECT_EQ(tracker->CanTrack(artkplus), is_artkplus) << name;
    EXPECT_EQ(tracker->CanTrack(runetag), is_runetag) << name;
    EXPECT_FALSE(tracker->CanTrack(other_family)) << name;
    for (const char* kind : {"circles_a", "circles_b", "circles_c", "circle_d"}) {
      const MarkerSpec circles = LoadMarkerYaml(std::string("scenarios/markers/") + kind + ".yaml");
      EXPECT_EQ(tracker->CanTrack(circles), is_circle) << name << " " << kind;
    }
    for (const char* kind : {"circle_e", "circle_f", "bit_grid", "dot_rings"}) {
      const MarkerSpec other = LoadMarkerYaml(std::string("scenarios/markers/") + kind + ".yaml");
      EXPECT_FALSE(tracker->CanTrack(other)) << name << " " << kind;
    }
  }
}

}  // namespace
}  // namespace markerbench
