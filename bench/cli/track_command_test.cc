#include "bench/cli/track_command.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <string>
#include <vector>

#include "bench/run/frames_csv.h"
#include "core/config_error.h"
#include "core/file_bytes.h"
#include "core/marker_yaml.h"
#include "core/test_files.h"
#include "renderer/image_io.h"
#include "renderer/render_frame.h"
#include "renderer/test_scenes.h"

namespace markerbench {
namespace {

using ::testing::HasSubstr;

std::vector<std::string> ReadLines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// An MJPEG video of a marker seen from `poses`, written with OpenCV's built-in encoder.
std::string WriteVideo(const std::string& marker_path,
                       const std::string& name,
                       const std::vector<Rigid3>& poses) {
  const MarkerSpec marker = LoadMarkerYaml(marker_path);
  const std::string path = WriteTestFile(name, "");
  cv::VideoWriter writer(path,
                         cv::CAP_OPENCV_MJPEG,
                         cv::VideoWriter::fourcc('M', 'J', 'P', 'G'),
                         10.0,
                         cv::Size(640, 480));
  EXPECT_TRUE(writer.isOpened());
  for (const Rigid3& pose : poses) {
    FrameRequest request;
    request.scene.marker = &marker;
    request.scene.cam_from_marker = pose;
    request.channels = 3;
    Image8 image = RenderFrame(request).image;
    const cv::Mat rgb(480, 640, CV_8UC3, image.pixels.data());
    cv::Mat bgr;
    cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
    writer.write(bgr);
  }
  return path;
}

TEST(TrackCommand, TracksEveryFrameOfAVideo) {
  TrackCommandOptions options;
  options.tracker = "apriltag";
  options.marker_path = "scenarios/markers/apriltag.yaml";
  options.camera_path = "scenarios/cameras/default.yaml";
  options.out_csv = WriteTestFile("track.csv", "");
  options.inputs = {WriteVideo(
      "scenarios/markers/apriltag.yaml",
      "tag.avi",
      {TiltedView(0.6, 20.0, 0.0), TiltedView(0.6, 20.0, 30.0), TiltedView(0.6, 20.0, 60.0)})};
  RunTrackCommand(options);
  const std::vector<std::string> rows = ReadLines(options.out_csv);
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0].rfind("image,tracker,status,r11", 0), 0u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NE(
        rows[static_cast<size_t>(i + 1)].find("tag.avi#" + std::to_string(i) + ",apriltag,ok,"),
        std::string::npos)
        << rows[static_cast<size_t>(i + 1)];
  }
}

// Runs `tracker` through a video of `marker_path` seen from `poses` (the command does not
// reset the tracker within a video) and checks every frame's camera centre.
void ExpectCentresThroughVideo(const std::string& tracker,
                               const std::string& marker_path,
                               const std::vector<Rigid3>& poses,
                               double center_tolerance_m) {
  TrackCommandOptions options;
  options.tracker = tracker;
  options.marker_path = marker_path;
  options.camera_path = "scenarios/cameras/default.yaml";
  options.out_csv = WriteTestFile(tracker + "_track.csv", "");
  options.inputs = {WriteVideo(options.marker_path, tracker + ".avi", poses)};
  RunTrackCommand(options);
  const std::vector<std::string> rows = ReadLines(options.out_csv);
  ASSERT_EQ(rows.size(), poses.size() + 1);
  const std::vector<std::string> header = SplitCsvLine(rows[0]);
  const size_t cam_x = std::find(header.begin(), header.end(), "cam_x_m") - header.begin();
  ASSERT_LT(cam_x + 2, header.size());
  for (size_t i = 0; i < poses.size(); ++i) {
    const std::vector<std::string> row = SplitCsvLine(rows[i + 1]);
    ASSERT_EQ(row[2], "ok") << rows[i + 1];
    const Eigen::Vector3d center(
        std::stod(row[cam_x]), std::stod(row[cam_x + 1]), std::stod(row[cam_x + 2]));
    EXPECT_LE((center - CameraCenterInMarker(poses[i])).norm(), center_tolerance_m) << i;
  }
}

constexpr double kVideoDistanceM = 0.6;
constexpr double kVideoCenterTolM = 0.01 * kVideoDistanceM;  // 1 % of the distance

std::vector<Rigid3> MovingView(double distance_m) {
  std::vector<Rigid3> poses;
  for (int i = 0; i < 5; ++i)
    poses.push_back(TiltedView(distance_m, 25.0 + 2.0 * i, 10.0 + 4.0 * i));
  return poses;
}

// circles_a: frames after the first run in tracking mode; the camera centres are right to
// 1 % of the distance despite MJPEG's chroma subsampling of the red and blue disks.
TEST(TrackCommand, TracksACircleMarkerThroughAVideo) {
  ExpectCentresThroughVideo(
      "circle", "scenarios/markers/circles_a.yaml", MovingView(kVideoDistanceM), kVideoCenterTolM);
}

// artkplus keeps its auto threshold from frame to frame within a video.
TEST(TrackCommand, TracksAnArtkPlusMarkerThroughAVideo) {
  ExpectCentresThroughVideo(
      "artkplus", "scenarios/markers/artkplus.yaml", MovingView(kVideoDistanceM), kVideoCenterTolM);
}

// runetag through MJPEG compression: its 2 mm inner dots survive the codec's blocks.
TEST(TrackCommand, TracksARuneTagMarkerThroughAVideo) {
  ExpectCentresThroughVideo(
      "runetag", "scenarios/markers/runetag.yaml", MovingView(kVideoDistanceM), kVideoCenterTolM);
}

// A PNG of the AprilTag seen at 0.6 m, at the default camera's size.
std::string WriteTagImage(const std::string& name) {
  const MarkerSpec marker = LoadMarkerYaml("scenarios/markers/apriltag.yaml");
  FrameRequest request;
  request.scene.marker = &marker;
  request.scene.cam_from_marker = TiltedView(0.6, 20.0, 0.0);
  const std::string path = WriteTestFile(name, "");
  WriteImage(path, RenderFrame(request).image);
  return path;
}

TrackCommandOptions TagOptions(const std::string& out_name) {
  TrackCommandOptions options;
  options.tracker = "apriltag";
  options.marker_path = "scenarios/markers/apriltag.yaml";
  options.camera_path = "scenarios/cameras/default.yaml";
  options.out_csv = out_name.empty() ? "" : WriteTestFile(out_name, "");
  return options;
}

std::string ConfigErrorOf(const TrackCommandOptions& options) {
  try {
    RunTrackCommand(options);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(TrackCommand, RefusesAnOutputThatIsAlsoAnInput) {
  const std::string image = WriteTagImage("own.png");
  const std::string bytes = ReadFileBytes(image);
  TrackCommandOptions options = TagOptions("");
  options.inputs = {image};
  const std::filesystem::path path(image);
  for (const std::string& out :
       {image, (path.parent_path() / "." / path.filename()).string(), options.camera_path}) {
    options.out_csv = out;
    EXPECT_THAT(ConfigErrorOf(options), HasSubstr("--out " + out + " is also an input"));
  }
  EXPECT_EQ(ReadFileBytes(image), bytes);
}

TEST(TrackCommand, RefusesInputsThatAreNotFiles) {
  TrackCommandOptions options = TagOptions("not_a_file.csv");
  const std::string folder = WriteTestFile("folder.png", "") + ".d.png";
  std::filesystem::create_directories(folder);
  options.inputs = {WriteTagImage("fine.png"), folder};
  EXPECT_THAT(ConfigErrorOf(options), HasSubstr(folder + ": expected a regular file"));
}

// Unreadable inputs are error rows naming the file; the readable ones are still tracked.
TEST(TrackCommand, BadImagesAreRowsAndTheRestIsTracked) {
  TrackCommandOptions options = TagOptions("mixed.csv");
  const std::string good = WriteTagImage("good.png");
  std::string truncated = ReadFileBytes(good);
  truncated.resize(truncated.size() / 2);
  Image8 small;
  small.width = 320;
  small.height = 240;
  small.channels = 1;
  small.pixels.assign(320 * 240, 128);
  const std::string wrong_size = WriteTestFile("small.png", "");
  WriteImage(wrong_size, small);
  options.inputs = {WriteTestFile("garbage.png", "not an image"),
                    WriteTestFile("truncated.png", truncated),
                    "/nonexistent/missing.png",
                    wrong_size,
                    WriteTestFile("garbage.avi", "not a video"),
                    good};
  RunTrackCommand(options);
  const std::vector<std::string> rows = ReadLines(options.out_csv);
  ASSERT_EQ(rows.size(), options.inputs.size() + 1);
  for (size_t i = 0; i + 1 < options.inputs.size(); ++i) {
    const std::vector<std::string> row = SplitCsvLine(rows[i + 1]);
    EXPECT_EQ(row[0], options.inputs[i]);
    EXPECT_EQ(row[2], "error") << rows[i + 1];
    EXPECT_FALSE(row.back().empty()) << "the message says why: " << rows[i + 1];
  }
  EXPECT_THAT(rows[4], HasSubstr("image is 320x240 but"));
  EXPECT_EQ(SplitCsvLine(rows.back())[2], "ok") << rows.back();

  options.inputs = {options.inputs[0], options.inputs[1], options.inputs[2], options.inputs[4]};
  EXPECT_THAT(ConfigErrorOf(options), HasSubstr("none of the 4 inputs could be read"));
}

TEST(TrackCommand, FileNamesAreQuoted) {
  TrackCommandOptions options = TagOptions("quoted.csv");
  const std::string image = WriteTagImage("a,\"b\".png");
  options.inputs = {image};
  RunTrackCommand(options);
  const std::vector<std::string> rows = ReadLines(options.out_csv);
  ASSERT_EQ(rows.size(), 2u);
  const std::vector<std::string> header = SplitCsvLine(rows[0]);
  const std::vector<std::string> row = SplitCsvLine(rows[1]);
  ASSERT_EQ(row.size(), header.size()) << rows[1];
  EXPECT_EQ(row[0], image);
  EXPECT_EQ(row[2], "ok");
}

}  // namespace
}  // namespace markerbench
