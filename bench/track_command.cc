#include "bench/track_command.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "bench/pose_columns.h"
#include "core/camera_yaml.h"
#include "core/marker_yaml.h"
#include "core/number_text.h"
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
    out_ << ",cam_x,cam_y,cam_z,time_ms\n";
  }

  void Write(const std::string& image,
             const std::string& tracker,
             const TrackResult& result,
             double time_ms) {
    out_ << image << ',' << tracker << ',' << ToString(result.status);
    if (result.status == TrackStatus::kOk && !result.hypotheses.empty()) {
      const Rigid3& pose = result.hypotheses.front();
      out_ << PoseFields(pose);
      const Eigen::Vector3d center = CameraCenterInMarker(pose);
      for (int i = 0; i < 3; ++i) out_ << ',' << NumberText(center[i]);
    } else {
      out_ << std::string(15, ',');
    }
    out_ << ',' << NumberText(time_ms) << '\n';
    out_.flush();
  }

 private:
  std::ostream& out_;
};

}  // namespace

void RunTrackCommand(const TrackCommandOptions& o) {
  const MarkerSpec marker = LoadMarkerYaml(o.marker_path);
  const Camera camera = LoadCameraYaml(o.camera_path);
  std::unique_ptr<Tracker> tracker = MakeTracker(o.tracker, nullptr);
  std::ofstream file;
  if (!o.out_csv.empty()) {
    file.open(o.out_csv);
    if (!file) throw std::runtime_error(o.out_csv + ": cannot write");
  }
  TrackCsv csv(o.out_csv.empty() ? &std::cout : &file);

  auto track = [&](const std::string& name, const Image8& image) {
    if (image.width != camera.width || image.height != camera.height) {
      throw ConfigError(name + ": image is " + std::to_string(image.width) + "x" +
                        std::to_string(image.height) + " but " + o.camera_path + " says " +
                        std::to_string(camera.width) + "x" + std::to_string(camera.height));
    }
    const auto start = std::chrono::steady_clock::now();
    TrackResult result;
    try {
      result = tracker->Track({&image, &camera, &marker});
    } catch (const std::exception& e) {
      result.status = TrackStatus::kError;
      result.message = e.what();
    }
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    csv.Write(name, o.tracker, result, ms);
  };

  for (const std::string& input : o.inputs) {
    if (IsImageFile(input)) {
      track(input, ReadImage(input));
      continue;
    }
    cv::VideoCapture video(input);
    if (!video.isOpened()) throw std::runtime_error(input + ": cannot open as image or video");
    tracker->Reset();  // a video is one sequence
    cv::Mat bgr, rgb;
    for (int frame = 0; video.read(bgr); ++frame) {
      cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
      Image8 image;
      image.width = rgb.cols;
      image.height = rgb.rows;
      image.channels = 3;
      image.pixels.assign(rgb.data, rgb.data + rgb.total() * 3);
      track(input + "#" + std::to_string(frame), image);
    }
  }
}

}  // namespace markerbench
