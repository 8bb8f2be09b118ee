#include "bench/cli/track_command.h"

#include <Eigen/Geometry>
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

#include "bench/io/atomic_file.h"
#include "bench/io/tum_trajectory.h"
#include "bench/run/frames_csv.h"
#include "bench/run/pose_columns.h"
#include "bench/run/pose_overlay.h"
#include "core/camera_yaml.h"
#include "core/gamma_curve.h"
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
    out_ << "image,tracker,status,hypotheses";
    for (const char* c : kPoseColumns) out_ << ',' << c;
    out_ << ",cam_x_m,cam_y_m,cam_z_m,time_ms,message,keypoints_px\n";
  }

  void Write(const std::string& image,
             const std::string& tracker,
             const TrackResult& result,
             double time_ms) {
    out_ << CsvField(image) << ',' << tracker << ',' << ToString(result.status) << ','
         << result.hypotheses.size();
    if (result.status == TrackStatus::kOk && !result.hypotheses.empty()) {
      const Rigid3& pose = result.hypotheses.front();
      out_ << PoseFields(pose);
      const Eigen::Vector3d center = CameraCenterInMarker(pose);
      for (int i = 0; i < 3; ++i) out_ << ',' << NumberText(center[i]);
    } else {
      out_ << std::string(15, ',');
    }
    out_ << ',' << (std::isnan(time_ms) ? "" : NumberText(time_ms)) << ','
         << CsvField(result.message) << ',';
    // The detected keypoints, "u v" pairs separated by ';' (as groundtruth.csv's).
    for (size_t k = 0; k < result.keypoints_px.size(); ++k) {
      out_ << (k ? ";" : "") << NumberText(result.keypoints_px[k].x()) << ' '
           << NumberText(result.keypoints_px[k].y());
    }
    out_ << '\n';
    out_.flush();
  }

 private:
  std::ostream& out_;
};

// Refuses, before anything is written, inputs that are not regular files and an output that
// is a folder or would overwrite one of the command's own inputs or the other output.
void CheckFiles(const TrackCommandOptions& o) {
  std::vector<std::string> read = o.inputs;
  read.push_back(o.marker_path);
  read.push_back(o.camera_path);
  for (const std::string& input : o.inputs) {
    if (std::filesystem::exists(input)) RequireRegularFile(input);
  }
  const auto same = [](const std::string& a, const std::string& b) {
    std::error_code error;
    return std::filesystem::equivalent(a, b, error) ||
           std::filesystem::weakly_canonical(a, error) ==
               std::filesystem::weakly_canonical(b, error);
  };
  const std::vector<std::pair<std::string, std::string>> outputs = {
      {"--out", o.out_csv}, {"--tum", o.tum_path}, {"--overlay", o.overlay_path}};
  for (const auto& [flag, output] : outputs) {
    if (output.empty()) continue;
    if (std::filesystem::is_directory(output)) {
      throw ConfigError(flag + " " + output + ": expected a file, but it is a folder");
    }
    for (const std::string& input : read) {
      if (same(output, input)) {
        throw ConfigError(flag + " " + output + " is also an input (" + input +
                          "); it would be overwritten");
      }
    }
  }
  for (size_t i = 0; i < outputs.size(); ++i) {
    for (size_t j = i + 1; j < outputs.size(); ++j) {
      if (!outputs[i].second.empty() && !outputs[j].second.empty() &&
          same(outputs[i].second, outputs[j].second)) {
        throw ConfigError(outputs[j].first + " " + outputs[j].second + " is also the " +
                          outputs[i].first + " file");
      }
    }
  }
}

// The tracker named in the options, with its --option settings, checked against the marker.
std::unique_ptr<Tracker> MakeCommandTracker(const TrackCommandOptions& o,
                                            const MarkerSpec& marker) {
  const YamlMap options = YamlMap::FromSettings("track", "--option", o.tracker_options);
  std::unique_ptr<Tracker> tracker =
      MakeTracker(o.tracker, o.tracker_options.empty() ? nullptr : &options);
  if (!tracker->CanTrack(marker)) {
    throw ConfigError("--tracker " + o.tracker + " cannot track " + o.marker_path + " (a " +
                      ToString(marker.kind) + " marker); markerbench list trackers shows the " +
                      "markers each tracker reads");
  }
  return tracker;
}

}  // namespace

void RunTrackCommand(const TrackCommandOptions& o) {
  if (!IsValidGamma(o.gamma)) {
    throw ConfigError("--gamma " + NumberText(o.gamma) + ": must be in [" + NumberText(kMinGamma) +
                      ", " + NumberText(kMaxGamma) + "]");
  }
  CheckFiles(o);
  const MarkerSpec marker = LoadMarkerYaml(o.marker_path);
  const Camera camera = LoadCameraYaml(o.camera_path);
  std::unique_ptr<Tracker> tracker = MakeCommandTracker(o, marker);
  std::ofstream file;
  if (!o.out_csv.empty()) {
    file.open(o.out_csv);
    if (!file) throw std::runtime_error(o.out_csv + ": cannot write: " + std::strerror(errno));
  }
  TrackCsv csv(o.out_csv.empty() ? &std::cout : &file);
  std::string tum;
  std::unique_ptr<PoseOverlay> overlay;
  if (!o.overlay_path.empty())
    overlay = std::make_unique<PoseOverlay>(o.overlay_path, camera, marker);

  // Frame `index` of a sequence at `fps` (images: 1 frame/s).
  auto track = [&](const std::string& name, const Image8& image, int index, double fps) {
    if (image.width != camera.width || image.height != camera.height) {
      csv.Write(name,
                o.tracker,
                ErrorResult("image is " + std::to_string(image.width) + "x" +
                            std::to_string(image.height) + " but " + o.camera_path + " says " +
                            std::to_string(camera.width) + "x" + std::to_string(camera.height)),
                NAN);
      return;
    }
    Image8 linear;  // the frame taken back to linear values, where --gamma says how
    const Image8* seen = &image;
    if (o.gamma != 1.0) {
      linear = Linearized(image, o.gamma);
      seen = &linear;
    }
    const auto start = std::chrono::steady_clock::now();
    const TrackResult result = TrackCatchingExceptions(tracker.get(), {seen, &camera, &marker});
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    csv.Write(name, o.tracker, result, ms);
    if (result.status == TrackStatus::kOk && !result.hypotheses.empty()) {
      tum += TumLine(index / fps, result.hypotheses.front());
    }
    if (overlay) overlay->Add(image, result, fps);
  };

  int inputs_read = 0;
  for (size_t index = 0; index < o.inputs.size(); ++index) {
    const std::string& input = o.inputs[index];
    if (IsImageFile(input)) {
      // Independent frames: no state from the previous image (no false lock on a pose that
      // belongs to another picture), unless the images are a sequence.
      if (!o.sequence) tracker->Reset();
      Image8 image;
      try {
        image = ReadImage(input);
      } catch (const std::exception& e) {
        csv.Write(input, o.tracker, ErrorResult(e.what()), NAN);
        continue;
      }
      ++inputs_read;
      track(input, image, static_cast<int>(index), 1.0);
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
    const double video_fps = video.get(cv::CAP_PROP_FPS);
    const double fps = video_fps > 0.0 ? video_fps : 1.0;
    int frame = 0;
    do {
      cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
      Image8 image;
      image.width = rgb.cols;
      image.height = rgb.rows;
      image.channels = 3;
      image.pixels.assign(rgb.data, rgb.data + rgb.total() * 3);
      track(input + "#" + std::to_string(frame), image, frame, fps);
      ++frame;
    } while (video.read(bgr));
  }
  if (inputs_read == 0) {
    throw ConfigError("track: none of the " + std::to_string(o.inputs.size()) +
                      " inputs could be read as an image or a video");
  }
  if (!o.tum_path.empty()) WriteFileAtomically(o.tum_path, tum);
}

}  // namespace markerbench
