#include "bench/cli/track_command.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "bench/run/frames_csv.h"
#include "bench/run/pose_columns.h"
#include "core/camera_yaml.h"
#include "core/marker_yaml.h"
#include "core/number_text.h"
#include "core/regular_file.h"
#include "core/yaml_reader.h"
#include "renderer/image_io.h"
#include "trackers/tracker_factory.h"

namespace markerbench {
namespace {

bool IsImageFile(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
  for (const char* e : {".png", ".jpg", ".jpeg", ".tif", ".tiff", ".bmp", ".exr", ".pgm", ".ppm"}) {
    if (ext == e) return true;
  }
  return false;
}

class TrackCsv {
 public:
  explicit TrackCsv(std::ostream* out) : out_(*out) {
    out_ << "image,tracker,status";
    for (const char* c : kPoseColumns) out_ << ',' << c;
    out_ << ",cam_x_m,cam_y_m,cam_z_m,time_ms,message\n";
  }

  void Write(const std::string& image,
             const std::string& tracker,
             const TrackResult& result,
             double time_ms) {
    out_ << CsvField(image) << ',' << tracker << ',' << ToString(result.status);
    if (result.status == TrackStatus::kOk && !result.hypotheses.empty()) {
      const Rigid3& pose = result.hypotheses.front();
      out_ << PoseFields(pose);
      const Eigen::Vector3d center = CameraCenterInMarker(pose);
      for (int i = 0; i < 3; ++i) out_ << ',' << NumberText(center[i]);
    } else {
      out_ << std::string(15, ',');
    }
    out_ << ',' << (std::isnan(time_ms) ? "" : NumberText(time_ms)) << ','
         << CsvField(result.message) << '\n';
    out_.flush();
  }

 private:
  std::ostream& out_;
};

// Refuses, before anything is written, inputs that are not regular files and an output that
// would overwrite one of the command's own inputs.
void CheckFiles(const TrackCommandOptions& o) {
  std::vector<std::string> read = o.inputs;
  read.push_back(o.marker_path);
  read.push_back(o.camera_path);
  for (const std::string& input : o.inputs) {
    if (std::filesystem::exists(input)) RequireRegularFile(input);
  }
  if (o.out_csv.empty()) return;
  if (std::filesystem::is_directory(o.out_csv)) {
    throw ConfigError("--out " + o.out_csv + ": expected a file, but it is a folder");
  }
  std::error_code error;
  for (const std::string& input : read) {
    if (std::filesystem::equivalent(o.out_csv, input, error) ||
        std::filesystem::weakly_canonical(o.out_csv, error) ==
            std::filesystem::weakly_canonical(input, error)) {
      throw ConfigError("--out " + o.out_csv + " is also an input (" + input +
                        "); it would be overwritten");
    }
  }
}

}  // namespace

void RunTrackCommand(const TrackCommandOptions& o) {
  CheckFiles(o);
  const MarkerSpec marker = LoadMarkerYaml(o.marker_path);
  const Camera camera = LoadCameraYaml(o.camera_path);
  std::unique_ptr<Tracker> tracker = MakeTracker(o.tracker, nullptr);
  std::ofstream file;
  if (!o.out_csv.empty()) {
    file.open(o.out_csv);
    if (!file) throw std::runtime_error(o.out_csv + ": cannot write: " + std::strerror(errno));
  }
  TrackCsv csv(o.out_csv.empty() ? &std::cout : &file);

  auto track = [&](const std::string& name, const Image8& image) {
    if (image.width != camera.width || image.height != camera.height) {
      csv.Write(name,
                o.tracker,
                ErrorResult("image is " + std::to_string(image.width) + "x" +
                            std::to_string(image.height) + " but " + o.camera_path + " says " +
                            std::to_string(camera.width) + "x" + std::to_string(camera.height)),
                NAN);
      return;
    }
    const auto start = std::chrono::steady_clock::now();
    const TrackResult result = TrackCatchingExceptions(tracker.get(), {&image, &camera, &marker});
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    csv.Write(name, o.tracker, result, ms);
  };

  int inputs_read = 0;
  for (const std::string& input : o.inputs) {
    if (IsImageFile(input)) {
      Image8 image;
      try {
        image = ReadImage(input);
      } catch (const std::exception& e) {
        csv.Write(input, o.tracker, ErrorResult(e.what()), NAN);
        continue;
      }
      ++inputs_read;
      track(input, image);
      continue;
    }
    // FFmpeg reads every common container; the default would also try GStreamer, which leaks
    // on files it cannot open.
    cv::VideoCapture video(input, cv::CAP_FFMPEG);
    cv::Mat bgr, rgb;
    if (!video.isOpened() || !video.read(bgr)) {
      csv.Write(input, o.tracker, ErrorResult(input + ": cannot read as an image or a video"), NAN);
      continue;
    }
    ++inputs_read;
    tracker->Reset();  // a video is one sequence
    int frame = 0;
    do {
      cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
      Image8 image;
      image.width = rgb.cols;
      image.height = rgb.rows;
      image.channels = 3;
      image.pixels.assign(rgb.data, rgb.data + rgb.total() * 3);
      track(input + "#" + std::to_string(frame++), image);
    } while (video.read(bgr));
  }
  if (inputs_read == 0) {
    throw ConfigError("track: none of the " + std::to_string(o.inputs.size()) +
                      " inputs could be read as an image or a video");
  }
}

}  // namespace markerbench
