// An external tracker speaking protocol 1 (trackers/external/testdata/scripted_tracker.py):
// requests carry the frame, results come back exactly, and every fault is that frame's error
// row with the program started again for the next frame.
#include "trackers/external/external_tracker.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/config_error.h"
#include "core/test_files.h"
#include "trackers/external/external_protocol.h"

namespace markerbench {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

const std::string kTestData = fs::current_path().string() + "/trackers/external/testdata/";

ExternalTrackerOptions ScriptedOptions(double timeout_s = 20.0) {
  ExternalTrackerOptions options;
  options.name = "scripted";
  options.command = {"python3", kTestData + "scripted_tracker.py", "scripted"};
  options.markers = {"tag"};
  options.timeout_s = timeout_s;
  const fs::path dir = fs::path(WriteTestFile("external.log", "")).parent_path();
  options.stderr_path = (dir / "external.log").string();
  options.image_dir = dir.string();
  options.marker_files = {{"tag", (dir / "tag.yaml").string()}};
  return options;
}

struct Frame {
  Image8 image;
  Camera camera;
  MarkerSpec marker;
  int64_t index = 0;

  explicit Frame(int64_t frame) : index(frame) {
    image.width = 40;
    image.height = 30;
    image.pixels.assign(40 * 30, 128);
    camera.fx = 612.5;
    marker.kind = MarkerKind::kAprilTag;
    marker.name = "tag";
  }
  Observation observation() const { return {&image, &camera, &marker, index}; }
};

TEST(ExternalTracker, ResultsComeBackExactly) {
  ExternalTracker tracker(ScriptedOptions());
  for (const int64_t frame : {0, 8, 10, 19}) {
    const TrackResult result = tracker.Track(Frame(frame).observation());
    ASSERT_EQ(result.status, TrackStatus::kOk) << result.message;
    ASSERT_EQ(result.hypotheses.size(), 1u);
    const double angle = 0.1 * static_cast<double>(frame);
    EXPECT_EQ(result.hypotheses[0].rotation(0, 0), std::cos(angle));
    EXPECT_EQ(result.hypotheses[0].rotation(1, 0), std::sin(angle));
    EXPECT_EQ(result.hypotheses[0].translation, Eigen::Vector3d(612.5, 40, 30));
    EXPECT_EQ(result.message, "apriltag tag.yaml channels 1 png yes frames 1");
    EXPECT_EQ(result.time_ms, 1.5);
    tracker.Reset();
  }
  // Without Reset the request says reset: false, and the program counts on.
  tracker.Track(Frame(0).observation());
  EXPECT_THAT(tracker.Track(Frame(0).observation()).message, HasSubstr("frames 2"));
  // Frames' images are removed after each reply.
  for (const auto& entry : fs::directory_iterator(ScriptedOptions().image_dir)) {
    EXPECT_THAT(entry.path().filename().string(), testing::Not(HasSubstr("scripted_")));
  }
}

TEST(ExternalTracker, EveryFaultIsAnErrorRowAndTheNextFrameIsTracked) {
  ExternalTracker tracker(ScriptedOptions(1.0));
  const std::vector<std::pair<int64_t, std::string>> faults = {
      {1, "the program was killed by signal SIGSEGV on this frame"},
      {2, "no reply within timeout_s 1 s; the program was stopped"},
      {3, "malformed reply: not a JSON object: 'this is not JSON'"},
      {4, "malformed reply: poses[0].R is not a rotation"},
      {5, "the program exited with status 3 on this frame"},
      {7, "malformed reply: not a JSON object"}};
  for (const auto& [frame, message] : faults) {
    const TrackResult result = tracker.Track(Frame(frame).observation());
    EXPECT_EQ(result.status, TrackStatus::kError) << frame;
    EXPECT_THAT(result.message, HasSubstr(message)) << frame;
    const TrackResult next = tracker.Track(Frame(10).observation());
    EXPECT_EQ(next.status, TrackStatus::kOk) << "after frame " << frame << ": " << next.message;
  }
  EXPECT_EQ(tracker.Track(Frame(6).observation()).status, TrackStatus::kNotDetected);
}

TEST(ExternalTracker, OnlyItsMarkers) {
  ExternalTracker tracker(ScriptedOptions());
  Frame other(0);
  other.marker.name = "other";
  EXPECT_FALSE(tracker.CanTrack(other.marker));
  EXPECT_TRUE(tracker.CanTrack(Frame(0).marker));
  EXPECT_EQ(tracker.Track(other.observation()).status, TrackStatus::kError);
}

TEST(ExternalTracker, AProgramThatCannotStartOrShakeHandsIsBadInput) {
  ExternalTrackerOptions missing = ScriptedOptions();
  missing.command = {"/nonexistent/tracker"};
  try {
    ExternalTracker tracker(missing);
    ADD_FAILURE();
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("tracker 'scripted' (/nonexistent/tracker)"));
  }
  ExternalTrackerOptions rude = ScriptedOptions();
  rude.command = {"python3", kTestData + "no_handshake.py"};
  try {
    ExternalTracker tracker(rude);
    ADD_FAILURE();
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("handshake: expected {\"protocol\": 1, \"ready\": true}"));
    EXPECT_THAT(e.what(), HasSubstr("hello?"));
  }
}

TEST(ExternalProtocol, RepliesAreChecked) {
  const std::string pose = R"({"R": [1, 0, 0, 0, 1, 0, 0, 0, 1], "t": [0, 0, 1]})";
  EXPECT_EQ(ParseReplyLine(R"({"status": "ok", "poses": [)" + pose + "]}").hypotheses.size(), 1u);
  for (
      const auto& [reply, complaint] : std::vector<std::pair<std::string, std::string>>{
          {R"({"status": "fine"})", "status \"fine\" is not one of"},
          {R"({"status": "ok"})", "status ok without a pose"},
          {R"({"status": "ok", "poses": [{"R": [1, 0, 0], "t": [0, 0, 1]}]})",
           "poses[0].R must be a list of 9 numbers"},
          {R"({"status": "ok", "poses": [{"R": [1, 0, 0, 0, 1, 0, 0, 0, -1], "t": [0, 0, 1]}]})",
           "not a rotation"},
          {R"({"status": "ok", "poses": [{"R": [1, 0, 0, 0, 1, 0, 0, 0, 1.00001], "t": [0, 0, 1]}]})",
           "not a rotation"},
          {R"({"status": "ok", "poses": [{"R": [1, 0, 0, 0, 1, 0, 0, 0, 1], "t": [0, "x", 1]}]})",
           "not a finite number"},
          {R"({"status": "error", "message": 3})", "message must be a string"},
          {R"({"status": "not_detected", "time_ms": -1})", "time_ms -1 is not a time"},
          {"[1, 2]", "not a JSON object"}}) {
    try {
      ParseReplyLine(reply);
      ADD_FAILURE() << reply;
    } catch (const std::runtime_error& e) {
      EXPECT_THAT(e.what(), HasSubstr(complaint)) << reply;
    }
  }
}

}  // namespace
}  // namespace markerbench
