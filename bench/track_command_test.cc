#include "bench/track_command.h"

#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <string>
#include <vector>

#include "core/marker_yaml.h"
#include "core/test_files.h"
#include "renderer/render_frame.h"
#include "renderer/test_scenes.h"

namespace markerbench {
namespace {

// A three-frame MJPEG video of the default AprilTag, written with OpenCV's built-in encoder.
std::string WriteTagVideo() {
  const MarkerSpec tag = LoadMarkerYaml("scenarios/markers/apriltag.yaml");
  const std::string path = WriteTestFile("tag.avi", "");
  cv::VideoWriter writer(path,
                         cv::CAP_OPENCV_MJPEG,
                         cv::VideoWriter::fourcc('M', 'J', 'P', 'G'),
                         10.0,
                         cv::Size(640, 480));
  EXPECT_TRUE(writer.isOpened());
  for (double roll : {0.0, 30.0, 60.0}) {
    FrameRequest request;
    request.scene.marker = &tag;
    request.scene.cam_from_marker = TiltedView(0.6, 20.0, roll);
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
  options.inputs = {WriteTagVideo()};
  RunTrackCommand(options);
  std::ifstream in(options.out_csv);
  std::string line;
  std::vector<std::string> rows;
  while (std::getline(in, line)) rows.push_back(line);
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0].rfind("image,tracker,status,r11", 0), 0u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NE(
        rows[static_cast<size_t>(i + 1)].find("tag.avi#" + std::to_string(i) + ",apriltag,ok,"),
        std::string::npos)
        << rows[static_cast<size_t>(i + 1)];
  }
}

}  // namespace
}  // namespace markerbench
