#include "trackers/tracker.h"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/camera_yaml.h"
#include "core/config_error.h"
#include "core/marker_yaml.h"
#include "core/number_text.h"
#include "core/yaml_reader.h"
#include "renderer/render_frame.h"
#include "renderer/test_scenes.h"
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
    const bool is_artkplus = name.rfind("artkplus", 0) == 0;
    const bool is_runetag = name.rfind("runetag", 0) == 0;
    EXPECT_EQ(tracker->CanTrack(apriltag), !is_aruco && !is_circle && !is_artkplus && !is_runetag)
        << name;
    EXPECT_EQ(tracker->CanTrack(aruco), is_aruco) << name;
    EXPECT_EQ(tracker->CanTrack(artkplus), is_artkplus) << name;
    EXPECT_EQ(tracker->CanTrack(runetag), is_runetag) << name;
    EXPECT_FALSE(tracker->CanTrack(other_family)) << name;
    for (const char* kind :
         {"circles_a", "circles_b", "circles_c", "circle_d", "circle_e", "circle_f"}) {
      const MarkerSpec circles = LoadMarkerYaml(std::string("scenarios/markers/") + kind + ".yaml");
      EXPECT_EQ(tracker->CanTrack(circles), is_circle) << name << " " << kind;
    }
    for (const char* kind : {"bit_grid", "dot_rings"}) {
      const MarkerSpec other = LoadMarkerYaml(std::string("scenarios/markers/") + kind + ".yaml");
      EXPECT_FALSE(tracker->CanTrack(other)) << name << " " << kind;
    }
  }
}

// The parameters that come with a tracker's name, not with its options (how AprilTag's and
// ArUco's adapters find the pose, the pixel convention's offset): listed, never read.
const std::map<std::string, std::set<std::string>> kFactsOfTheName = {
    {"apriltag", {"pose", "pixel_offset_corrected"}},
    {"apriltag-ippe", {"pose", "pixel_offset_corrected"}},
    {"aruco", {"pose"}}};

bool IsFactOfTheName(const std::string& name, const std::string& key) {
  const auto named = kFactsOfTheName.find(name);
  return named != kFactsOfTheName.end() && named->second.count(key);
}

// A run records each tracker's Parameters() (its manifest, `markerbench list trackers`): read
// back as options they must build the same tracker, every key but the name's facts read back as
// written.
TEST(TrackerFactory, ParametersReadBackAsOptionsGiveTheSameTracker) {
  for (const std::string& name : TrackerNames()) {
    const std::vector<std::pair<std::string, std::string>> parameters =
        MakeTracker(name, nullptr)->Parameters();
    ASSERT_FALSE(parameters.empty()) << name;
    YAML::Node node(YAML::NodeType::Map);
    for (const auto& [key, value] : parameters) {
      if (!IsFactOfTheName(name, key)) node[key] = YAML::Load(value);
    }
    const YamlMap options(node, "parameters of " + name, "");
    EXPECT_EQ(MakeTracker(name, &options)->Parameters(), parameters) << name;
  }
}

// Each number and switch of a tracker's Parameters() set alone to another value it accepts: the
// tracker's parameters are its defaults with that key's value changed, and nothing else. A key
// read into another field than the one it is written from, or read as the wrong type, fails.
TEST(TrackerFactory, EachParameterSetAloneChangesItselfAlone) {
  for (const std::string& name : TrackerNames()) {
    const std::vector<std::pair<std::string, std::string>> defaults =
        MakeTracker(name, nullptr)->Parameters();
    for (size_t i = 0; i < defaults.size(); ++i) {
      const auto& [key, text] = defaults[i];
      if (IsFactOfTheName(name, key)) continue;
      std::vector<std::string> others;
      if (text == "true" || text == "false") {
        others = {text == "true" ? "false" : "true"};
      } else if (const std::optional<double> value = ParseFiniteNumber(text)) {
        for (double other : {*value + 1.0, *value - 1.0, *value + 2.0, *value * 0.5}) {
          others.push_back(NumberText(other));
        }
      } else {
        continue;  // a name: its own tracker's tests read each
      }
      bool accepted = false;
      for (const std::string& other : others) {
        YAML::Node node(YAML::NodeType::Map);
        node[key] = YAML::Load(other);
        const YamlMap options(node, name + " with " + key + ": " + other, "");
        std::unique_ptr<Tracker> tracker;
        try {
          tracker = MakeTracker(name, &options);
        } catch (const ConfigError&) {
          continue;  // outside the key's range: try the next value
        }
        std::vector<std::pair<std::string, std::string>> expected = defaults;
        expected[i].second = other;
        EXPECT_EQ(tracker->Parameters(), expected) << options.file();
        accepted = true;
        break;
      }
      EXPECT_TRUE(accepted) << name << ": no other value of " << key << " accepted";
    }
  }
}

// Images a camera cannot give a marker in (1x1, a 4 px strip, an empty image) are frames like
// any other: a status, never a crash. libapriltag dies on images 4 px tall or less.
TEST(TrackerFactory, EveryTrackerSurvivesDegenerateImages) {
  for (const std::string& name : TrackerNames()) {
    const auto tracker = MakeTracker(name, nullptr);
    std::vector<MarkerSpec> markers;
    for (const char* kind : {"apriltag", "aruco", "artkplus", "runetag", "circles_a", "circle_d"}) {
      markers.push_back(LoadMarkerYaml(std::string("scenarios/markers/") + kind + ".yaml"));
    }
    const Camera camera = LoadCameraYaml("scenarios/cameras/default.yaml");
    for (const auto& [width, height] : std::vector<std::pair<int, int>>{{0, 0},
                                                                        {1, 1},
                                                                        {2, 2},
                                                                        {640, 4},
                                                                        {4, 480},
                                                                        {640, 1},
                                                                        {7, 7},
                                                                        {640, 8},
                                                                        {8, 480},
                                                                        {9, 9}}) {
      for (const int channels : {1, 3}) {
        Image8 image;
        image.width = width;
        image.height = height;
        image.channels = channels;
        image.pixels = std::vector<uint8_t>(static_cast<size_t>(width) * height * channels, 128);
        for (const MarkerSpec& marker : markers) {
          if (!tracker->CanTrack(marker)) continue;
          tracker->Reset();
          const TrackResult result = tracker->Track({&image, &camera, &marker});
          EXPECT_NE(result.status, TrackStatus::kOk)
              << name << " " << width << "x" << height << "x" << channels;
        }
      }
    }
    Image8 short_buffer;
    short_buffer.width = short_buffer.height = 64;
    short_buffer.pixels = std::vector<uint8_t>(100, 0);
    const TrackResult result = tracker->Track({&short_buffer, &camera, &markers.front()});
    EXPECT_EQ(result.status, TrackStatus::kError) << name;
    EXPECT_EQ(result.message, "malformed image 64x64x1 with 100 bytes") << name;
  }
}

// A tracker reads the frame and writes nothing into it: a sweep hands the same frame to each of
// its trackers in turn, and the frame goes into the example video after them. On noisy frames
// of every marker it can track, grey and RGB, detected and then tracked. (`runetag-improved`
// blurred grey frames in place against their noise, so that a tracker after it read them
// blurred.)
TEST(TrackerFactory, NoTrackerWritesIntoTheFrame) {
  const Camera camera = LoadCameraYaml("scenarios/cameras/default.yaml");
  std::vector<MarkerSpec> markers;
  for (const char* kind : {"apriltag",
                           "aruco",
                           "artkplus",
                           "runetag",
                           "circles_a",
                           "circle_d",
                           "circle_e",
                           "circle_f"}) {
    markers.push_back(LoadMarkerYaml(std::string("scenarios/markers/") + kind + ".yaml"));
  }
  for (const std::string& name : TrackerNames()) {
    const auto tracker = MakeTracker(name, nullptr);
    for (const MarkerSpec& marker : markers) {
      if (!tracker->CanTrack(marker)) continue;
      for (const int channels : {1, 3}) {
        tracker->Reset();
        for (uint64_t seed = 0; seed < 2; ++seed) {
          FrameRequest request =
              MarkerFrameRequest(marker, TiltedView(0.5, 20.0, 30.0), 0.05, 1.0, channels);
          request.noise_seed = seed;
          const RenderedFrame frame = RenderFrame(request);
          const std::vector<uint8_t> before = frame.image.pixels;
          tracker->Track({&frame.image, &camera, &marker});
          EXPECT_TRUE(frame.image.pixels == before)
              << name << " on " << marker.name << ", " << channels << " channels, frame " << seed;
        }
      }
    }
  }
}

}  // namespace
}  // namespace markerbench
