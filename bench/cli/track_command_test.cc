#include "bench/cli/track_command.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "bench/plan/frame_plan.h"
#include "bench/plan/marker_files.h"
#include "bench/plan/scenario.h"
#include "bench/run/frames_csv.h"
#include "bench/run/pose_overlay.h"
#include "core/camera_yaml.h"
#include "core/config_error.h"
#include "core/file_bytes.h"
#include "core/gamma_curve.h"
#include "core/marker_yaml.h"
#include "core/number_text.h"
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

// Options for `tracker` on the marker file `marker_path`, the default camera, the CSV in a
// test file `out_name` (empty: standard output).
TrackCommandOptions OptionsFor(const std::string& tracker,
                               const std::string& marker_path,
                               const std::string& out_name) {
  TrackCommandOptions options;
  options.tracker = tracker;
  options.marker_path = marker_path;
  options.camera_path = "scenarios/cameras/default.yaml";
  options.out_csv = out_name.empty() ? "" : WriteTestFile(out_name, "");
  return options;
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
  TrackCommandOptions options =
      OptionsFor("apriltag", "scenarios/markers/apriltag.yaml", "track.csv");
  options.inputs = {WriteVideo(
      "scenarios/markers/apriltag.yaml",
      "tag.avi",
      {TiltedView(0.6, 20.0, 0.0), TiltedView(0.6, 20.0, 30.0), TiltedView(0.6, 20.0, 60.0)})};
  RunTrackCommand(options);
  const std::vector<std::string> rows = ReadLines(options.out_csv);
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0].rfind("image,tracker,status,hypotheses,r11", 0), 0u);
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
  TrackCommandOptions options = OptionsFor(tracker, marker_path, tracker + "_track.csv");
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

// artkplus keeps its auto threshold from frame to frame within a video (the improved
// variant: the faithful one's +1 % depth bias exceeds the tolerance).
TEST(TrackCommand, TracksAnArtkPlusMarkerThroughAVideo) {
  ExpectCentresThroughVideo("artkplus-improved",
                            "scenarios/markers/artkplus.yaml",
                            MovingView(kVideoDistanceM),
                            kVideoCenterTolM);
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
  return OptionsFor("apriltag", "scenarios/markers/apriltag.yaml", out_name);
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
  const std::vector<std::string> header = SplitCsvLine(rows[0]);
  const size_t message = std::find(header.begin(), header.end(), "message") - header.begin();
  for (size_t i = 0; i + 1 < options.inputs.size(); ++i) {
    const std::vector<std::string> row = SplitCsvLine(rows[i + 1]);
    EXPECT_EQ(row[0], options.inputs[i]);
    EXPECT_EQ(row[2], "error") << rows[i + 1];
    ASSERT_LT(message, row.size());
    EXPECT_FALSE(row[message].empty()) << "the message says why: " << rows[i + 1];
  }
  EXPECT_THAT(rows[4], HasSubstr("image is 320x240 but"));
  EXPECT_EQ(SplitCsvLine(rows.back())[2], "ok") << rows.back();

  options.inputs = {options.inputs[0], options.inputs[1], options.inputs[2], options.inputs[4]};
  EXPECT_THAT(ConfigErrorOf(options), HasSubstr("none of the 4 inputs could be read"));
}

// A PNG of circles_a seen from `pose`.
std::string WriteCirclesImage(const std::string& name, const Rigid3& pose) {
  const MarkerSpec marker = LoadMarkerYaml("scenarios/markers/circles_a.yaml");
  FrameRequest request;
  request.scene.marker = &marker;
  request.scene.cam_from_marker = pose;
  request.channels = 3;
  request.degradations.noise_var = 0.01;
  const std::string path = WriteTestFile(name, "");
  WriteImage(path, RenderFrame(request).image);
  return path;
}

// The rows of a track CSV after its header, without the time column (a measurement).
std::vector<std::string> RowsWithoutTime(const std::string& csv) {
  std::vector<std::string> rows = ReadLines(csv);
  const std::vector<std::string> header = SplitCsvLine(rows.at(0));
  const size_t time = std::find(header.begin(), header.end(), "time_ms") - header.begin();
  std::vector<std::string> kept;
  for (size_t i = 1; i < rows.size(); ++i) {
    std::vector<std::string> row = SplitCsvLine(rows[i]);
    row.erase(row.begin() + static_cast<std::ptrdiff_t>(time));
    std::string line;
    for (const std::string& field : row) line += field + "|";
    kept.push_back(line);
  }
  return kept;
}

// Images are independent frames: a picture gives the same row whatever came before it (the
// circle tracker's tracking mode would otherwise start from the previous picture's pose).
// With --sequence the tracker keeps its state.
TEST(TrackCommand, ImagesAreIndependentUnlessASequence) {
  const std::string a = WriteCirclesImage("a.png", TiltedView(0.6, 20.0, 10.0));
  const std::string b = WriteCirclesImage("b.png", TiltedView(0.6, 23.0, 13.0));
  TrackCommandOptions options =
      OptionsFor("circle", "scenarios/markers/circles_a.yaml", "alone.csv");
  options.inputs = {a};
  RunTrackCommand(options);
  const std::vector<std::string> alone = RowsWithoutTime(options.out_csv);
  ASSERT_EQ(alone.size(), 1u);
  EXPECT_THAT(alone[0], HasSubstr("|circle|ok|1|"));

  options.out_csv = WriteTestFile("independent.csv", "");
  options.inputs = {b, a};
  RunTrackCommand(options);
  EXPECT_EQ(RowsWithoutTime(options.out_csv).at(1), alone[0]);

  options.out_csv = WriteTestFile("sequence.csv", "");
  options.sequence = true;
  RunTrackCommand(options);
  const std::vector<std::string> sequence = RowsWithoutTime(options.out_csv);
  EXPECT_THAT(sequence.at(1), HasSubstr("|circle|ok|1|"));
  EXPECT_NE(sequence.at(1), alone[0]) << "tracking mode starts from b's pose";
}

// A camera's frames are gamma-encoded, not linear in the light as the renderer's: circle_f seen
// through an encoding gamma of 2.2 (1.5 px blur, 2.5 grey levels of noise) has every blurred edge
// bent (its wedge is read at the level it shows, so it is still found, measured 23 mm off);
// --gamma 2.2 takes the frame back to linear values and the pose is found within a millimetre
// (measured: 0.24 mm).
TEST(TrackCommand, GammaLinearizesTheFramesForTheTracker) {
  const std::string marker_path = "scenarios/markers/circle_f.yaml";
  const MarkerSpec marker = LoadMarkerYaml(marker_path);
  const Rigid3 truth = TiltedView(0.8, 25.0, 30.0);
  FrameRequest request;
  request.scene.marker = &marker;
  request.scene.cam_from_marker = truth;
  request.degradations.noise_var = 1e-4;
  request.degradations.blur_sigma_px = 1.5;
  Image8 encoded = RenderFrame(request).image;
  ApplyGammaCurve(1.0 / 2.2, &encoded);
  const std::string image = WriteTestFile("gamma_encoded.png", "");
  WriteImage(image, encoded);

  TrackCommandOptions options = OptionsFor("circle", marker_path, "as_linear.csv");
  options.inputs = {image};
  // The position error of the pose in the output, infinity where there is none.
  const auto position_error = [&] {
    RunTrackCommand(options);
    const std::vector<std::string> lines = ReadLines(options.out_csv);
    const std::vector<std::string> header = SplitCsvLine(lines.at(0));
    const std::vector<std::string> row = SplitCsvLine(lines.at(1));
    if (row.at(2) != "ok") return std::numeric_limits<double>::infinity();
    Eigen::Vector3d t;
    for (int i = 0; i < 3; ++i) {
      const auto column = std::find(header.begin(), header.end(), std::string("t") + "xyz"[i]);
      t[i] = std::stod(row.at(static_cast<size_t>(column - header.begin())));
    }
    return (t - truth.translation).norm();
  };
  const double as_linear = position_error();
  EXPECT_GT(as_linear, 2e-3);

  options.out_csv = WriteTestFile("linearized.csv", "");
  options.gamma = 2.2;
  EXPECT_LT(position_error(), 1e-3);

  // The renderer's range (core/gamma_curve.h), NaN outside it.
  for (const double gamma : {0.0, 0.09, 10.5, std::nan("")}) {
    options.gamma = gamma;
    EXPECT_THAT(ConfigErrorOf(options),
                HasSubstr("--gamma " + NumberText(gamma) + ": must be in [0.1, 10]"));
  }
}

// The tracker, its options and the marker are checked before any frame is read.
TEST(TrackCommand, TrackerOptionsAndMarkerAreCheckedFirst) {
  TrackCommandOptions options = TagOptions("checked.csv");
  options.inputs = {"/nonexistent/never_read.png"};
  options.tracker_options = {"quad_decimate=fast"};
  EXPECT_THAT(ConfigErrorOf(options),
              HasSubstr("track (--option quad_decimate=fast): key 'quad_decimate': expected a "
                        "number, got 'fast'"));
  options.tracker_options = {"quad_decimation=2"};
  EXPECT_THAT(ConfigErrorOf(options), HasSubstr("key 'quad_decimation': unknown key"));
  options.tracker_options = {"quad_decimate"};
  EXPECT_THAT(ConfigErrorOf(options), HasSubstr("--option quad_decimate: expected KEY=VALUE"));
  options.tracker_options = {"quad_decimate=[1"};
  EXPECT_THAT(ConfigErrorOf(options), HasSubstr("the value is not valid YAML"));
  options.tracker_options = {};
  options.marker_path = "scenarios/markers/circles_a.yaml";
  EXPECT_THAT(ConfigErrorOf(options), HasSubstr("--tracker apriltag cannot track"));
  EXPECT_TRUE(ReadFileBytes(options.out_csv).empty()) << "nothing written";
  // A valid option reaches the tracker.
  options = TagOptions("decimated.csv");
  options.inputs = {WriteTagImage("decimated.png")};
  options.tracker_options = {"quad_decimate=1.0"};
  RunTrackCommand(options);
  EXPECT_THAT(ReadLines(options.out_csv).at(1), HasSubstr(",apriltag,ok,"));
}

// circle on a circles_a video of the MovingView poses; the CSV is `name`.csv.
TrackCommandOptions CirclesVideoOptions(const std::string& name) {
  TrackCommandOptions options =
      OptionsFor("circle", "scenarios/markers/circles_a.yaml", name + ".csv");
  options.inputs = {WriteVideo(options.marker_path, name + ".avi", MovingView(kVideoDistanceM))};
  return options;
}

// --tum: one line per tracked frame, the camera in the marker frame (the CSV's camera centre
// and the inverse of its rotation), so that evo and the TUM tools read it.
TEST(TrackCommand, TumTrajectoryOfAVideo) {
  TrackCommandOptions options = CirclesVideoOptions("tum");
  options.tum_path = WriteTestFile("track.tum", "");
  const std::vector<Rigid3> poses = MovingView(kVideoDistanceM);
  RunTrackCommand(options);
  const std::vector<std::string> rows = ReadLines(options.out_csv);
  const std::vector<std::string> tum = ReadLines(options.tum_path);
  ASSERT_EQ(tum.size(), poses.size());
  const std::vector<std::string> header = SplitCsvLine(rows[0]);
  const size_t r11 = std::find(header.begin(), header.end(), "r11") - header.begin();
  const size_t cam_x = std::find(header.begin(), header.end(), "cam_x_m") - header.begin();
  for (size_t i = 0; i < poses.size(); ++i) {
    const std::vector<std::string> row = SplitCsvLine(rows[i + 1]);
    std::istringstream line(tum[i]);
    double t, x, y, z, qx, qy, qz, qw;
    ASSERT_TRUE(line >> t >> x >> y >> z >> qx >> qy >> qz >> qw) << tum[i];
    EXPECT_NEAR(t, i / 10.0, 1e-9);  // the video's 10 frames/s
    EXPECT_NEAR(x, std::stod(row[cam_x]), 1e-12);
    EXPECT_NEAR(y, std::stod(row[cam_x + 1]), 1e-12);
    EXPECT_NEAR(z, std::stod(row[cam_x + 2]), 1e-12);
    const Eigen::Quaterniond q(qw, qx, qy, qz);
    EXPECT_NEAR(q.norm(), 1.0, 1e-12);
    Eigen::Matrix3d cam_from_marker;
    for (int k = 0; k < 9; ++k) cam_from_marker(k / 3, k % 3) = std::stod(row[r11 + k]);
    EXPECT_LT((q.toRotationMatrix() - cam_from_marker.transpose()).norm(), 1e-9) << i;
  }
}

// Whether an overlay frame has the y axis's green within 2 px of `px` (circles_a has no green).
bool GreenNear(const cv::Mat& bgr, const Eigen::Vector2d& px) {
  for (int dy = -2; dy <= 2; ++dy) {
    for (int dx = -2; dx <= 2; ++dx) {
      const cv::Vec3b c = bgr.at<cv::Vec3b>(static_cast<int>(std::lround(px.y())) + dy,
                                            static_cast<int>(std::lround(px.x())) + dx);
      if (c[1] > 150 && c[0] < 110 && c[2] < 110) return true;
    }
  }
  return false;
}

// The video at options.overlay_path has a frame per pose of `truths`, each with the y axis
// drawn where that pose projects it and no green beside it.
void ExpectAxesWhereTheTruthProjectsThem(const TrackCommandOptions& options,
                                         const std::vector<Rigid3>& truths) {
  const MarkerSpec marker = LoadMarkerYaml(options.marker_path);
  const Camera camera = LoadCameraYaml(options.camera_path);
  const double axis_m = PoseOverlay(options.overlay_path, camera, marker).AxisLengthM();
  cv::VideoCapture video(options.overlay_path, cv::CAP_FFMPEG);
  ASSERT_TRUE(video.isOpened());
  cv::Mat bgr;
  size_t frames = 0;
  for (; video.read(bgr); ++frames) {
    ASSERT_LT(frames, truths.size());
    const Rigid3& truth = truths[frames];
    for (const double t : {0.3, 0.6, 0.9}) {
      const Eigen::Vector2d on_axis = camera.ImgFromCam(truth * Eigen::Vector3d(0, t * axis_m, 0));
      EXPECT_TRUE(GreenNear(bgr, on_axis)) << "frame " << frames << " at " << t;
    }
    // Beside the axis (a tenth of its length away along x), no green.
    const Eigen::Vector2d beside =
        camera.ImgFromCam(truth * Eigen::Vector3d(0.1 * axis_m, 0.6 * axis_m, 0));
    EXPECT_FALSE(GreenNear(bgr, beside)) << "frame " << frames;
  }
  EXPECT_EQ(frames, truths.size());
}

// --overlay: every frame with the pose drawn; the y axis (green; circles_a has no green)
// lies where the true pose projects it.
TEST(TrackCommand, OverlayDrawsTheAxesWhereTheTruthProjectsThem) {
  TrackCommandOptions options = CirclesVideoOptions("overlay_in");
  options.overlay_path = WriteTestFile("overlay.mp4", "");
  RunTrackCommand(options);
  ExpectAxesWhereTheTruthProjectsThem(options, MovingView(kVideoDistanceM));
}

// A test video made from a sequence scenario (issue 22): the orbit's first moving second of
// circles_a (scenarios/sequences/orbit.yaml, no noise), tracked as a video with --overlay;
// every frame is tracked and the drawn y axis lies where the frame's ground truth projects it.
TEST(TrackCommand, OverlayOfAVideoFromASequenceScenario) {
  const Scenario scenario = LoadScenario("scenarios/sequences/orbit.yaml");
  constexpr int kStillFrames = 30, kFrames = 60;  // the orbit holds still for 1 s at 30 fps
  const std::vector<PlannedFrame> plan = PlanFrames(scenario, kFrames);
  const std::string video_path = WriteTestFile("orbit.avi", "");
  cv::VideoWriter writer(video_path,
                         cv::CAP_OPENCV_MJPEG,
                         cv::VideoWriter::fourcc('M', 'J', 'P', 'G'),
                         scenario.trajectory->fps,
                         cv::Size(640, 480));
  ASSERT_TRUE(writer.isOpened());
  std::vector<Rigid3> truths;
  for (int k = kStillFrames; k < kFrames; ++k) {
    ASSERT_EQ(plan[k].sequence_frame, k);
    Image8 image = RenderFrame(RequestFor(scenario, plan[k])).image;
    ASSERT_EQ(image.channels, 3);
    const cv::Mat rgb(480, 640, CV_8UC3, image.pixels.data());
    cv::Mat bgr;
    cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
    writer.write(bgr);
    truths.push_back(plan[k].cam_from_marker);
  }
  writer.release();
  // The marker file as the scenario scales it (equal ink area), beside the video.
  const std::string folder = std::filesystem::path(video_path).parent_path().string();
  TrackCommandOptions options =
      OptionsFor("circle", WriteScaledMarkerFiles(scenario, folder).at("circles_a"), "orbit.csv");
  options.inputs = {video_path};
  options.overlay_path = WriteTestFile("orbit_overlay.mp4", "");
  RunTrackCommand(options);
  ExpectAxesWhereTheTruthProjectsThem(options, truths);
  const std::vector<std::string> rows = ReadLines(options.out_csv);
  ASSERT_EQ(rows.size(), 1 + truths.size());
  for (size_t i = 1; i < rows.size(); ++i) EXPECT_THAT(rows[i], HasSubstr(",ok,")) << rows[i];
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
