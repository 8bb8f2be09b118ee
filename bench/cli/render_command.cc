#include "bench/cli/render_command.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "bench/io/output_folder.h"
#include "bench/io/progress.h"
#include "bench/plan/frame_plan.h"
#include "bench/plan/marker_files.h"
#include "bench/run/dataset.h"
#include "bench/run/frame_bound.h"
#include "bench/run/frames_csv.h"
#include "bench/run/pose_columns.h"
#include "core/camera_yaml.h"
#include "core/joined.h"
#include "core/marker_yaml.h"
#include "core/number_text.h"
#include "core/random.h"
#include "core/regular_file.h"
#include "core/yaml_reader.h"
#include "renderer/image_io.h"
#include "renderer/render_frame.h"

namespace markerbench {
namespace {

// Where a groundtruth.csv row's frame comes from: the sweep's cell and trial (empty for
// explicit poses) and, in a sequence, its place in the video.
struct FrameOrigin {
  std::string sweep_parameter, sweep_value, grid, trial;
  int sequence_frame = -1;  // -1: not a sequence
  double time_s = NAN;      // the ground truth's time in its sequence
  bool occluded = false;
};

// One groundtruth.csv row per rendered frame.
class GroundTruthCsv {
 public:
  explicit GroundTruthCsv(const std::string& dir) : path_(dir + "/groundtruth.csv"), out_(path_) {
    if (!out_) throw std::runtime_error(path_ + ": cannot write");
    out_ << "frame,image,marker,sweep_parameter,sweep_value,grid,trial,seed,fx,fy,cx,cy,width,"
            "height";
    for (const char* c : kPoseColumns) out_ << ',' << c;
    out_ << ",noise_var,blur_sigma_px,motion_blur_px,motion_blur_angle_deg,gain,offset,gamma,"
            "jpeg_quality,channels,apparent_size_px,keypoints_px,sequence_frame,time_s,occluded,"
            "exposure_s,readout_s";
    for (const std::string& c : FrameBoundColumns()) out_ << ',' << c;
    out_ << '\n';
  }

  void Write(int frame,
             const std::string& image,
             const std::string& marker,
             const FrameOrigin& origin,
             uint64_t seed,
             const Camera& camera,
             const FrameRequest& request,
             const GroundTruth& truth,
             const FrameBound& bound) {
    out_ << frame << ',' << CsvField(image) << ',' << CsvField(marker) << ','
         << origin.sweep_parameter << ',' << origin.sweep_value << ',' << CsvField(origin.grid)
         << ',' << origin.trial << ',' << seed << ',' << NumberText(camera.fx) << ','
         << NumberText(camera.fy) << ',' << NumberText(camera.cx) << ',' << NumberText(camera.cy)
         << ',' << camera.width << ',' << camera.height;
    out_ << PoseFields(truth.cam_from_marker);
    const Degradations& d = request.degradations;
    out_ << ',' << NumberText(d.noise_var) << ',' << NumberText(d.blur_sigma_px) << ','
         << NumberText(d.motion_blur_px) << ',' << NumberText(d.motion_blur_angle_deg) << ','
         << NumberText(d.gain) << ',' << NumberText(d.offset) << ',' << NumberText(d.gamma) << ','
         << d.jpeg_quality << ',' << request.channels << ',' << NumberText(truth.apparent_size_px)
         << ',';
    for (size_t k = 0; k < truth.keypoints_px.size(); ++k) {
      out_ << (k ? ";" : "") << NumberText(truth.keypoints_px[k].x()) << ' '
           << NumberText(truth.keypoints_px[k].y());
    }
    out_ << ',' << (origin.sequence_frame >= 0 ? std::to_string(origin.sequence_frame) : "") << ','
         << NumberTextOrEmpty(origin.time_s) << ',' << int{origin.occluded} << ','
         << NumberText(request.exposure_s) << ',' << NumberText(request.readout_s)
         << FrameBoundFields(bound) << '\n';
    out_.flush();
  }

 private:
  std::string path_;
  std::ofstream out_;
};

std::string FrameName(int index, const char* extension) {
  char name[32];
  std::snprintf(name, sizeof(name), "frame_%06d.%s", index, extension);
  return name;
}

// Writes the PNG (and the EXR when asked); returns the PNG's name.
std::string WriteFrame(const std::string& dir, int index, const RenderedFrame& frame) {
  const std::string png = FrameName(index, "png");
  WriteImage(dir + "/" + png, frame.image);
  if (!frame.linear.data.empty())
    WriteImageFloat(dir + "/" + FrameName(index, "exr"), frame.linear);
  return png;
}

}  // namespace

void RenderScenario(const std::string& scenario_path,
                    const std::string& out_dir,
                    int limit,
                    bool write_float,
                    bool overwrite) {
  const Scenario scenario = LoadScenario(scenario_path);
  const std::vector<PlannedFrame> frames = PlanFrames(scenario, limit);
  CreateEmptyOutputFolder(out_dir, overwrite);
  WriteDatasetFiles(out_dir,
                    scenario.name,
                    scenario_path,
                    scenario.input_files[1],
                    WriteScaledMarkerFiles(scenario, out_dir + "/markers"));
  GroundTruthCsv csv(out_dir);
  Progress progress("render " + scenario.name, frames.size(), 0);
  for (const PlannedFrame& f : frames) {
    FrameRequest request = RequestFor(scenario, f);
    request.keep_linear = write_float;
    const RenderedFrame frame = RenderFrame(request);
    const std::string image = WriteFrame(out_dir, f.index, frame);
    FrameOrigin origin{
        scenario.sweep_parameter, NumberText(f.sweep_value), f.grid, std::to_string(f.trial)};
    if (f.sequence_frame >= 0) {
      origin.sequence_frame = f.sequence_frame;
      origin.time_s = scenario.trajectory->TruthTime(f.sequence_frame);
      origin.occluded = f.occluded;
    }
    csv.Write(f.index,
              image,
              request.scene.marker->name,
              origin,
              scenario.seed,
              scenario.camera,
              request,
              frame.truth,
              PlannedFrameBound(scenario, f, request));
    progress.Advance();
  }
  progress.Finish();
}

std::vector<Rigid3> LoadPosesCsv(const std::string& path) {
  RequireRegularFile(path);
  std::ifstream in(path);
  if (!in) throw ConfigError(path + ": cannot open the file");
  std::string line;
  std::getline(in, line);
  const std::string expected_header =
      Joined({std::begin(kPoseColumns), std::end(kPoseColumns)}, ",");
  if (line != expected_header && line != expected_header + "\r") {
    throw ConfigError(path + ":1: header: expected '" + expected_header + "', got '" + line + "'");
  }
  std::vector<Rigid3> poses;
  int line_number = 1;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty() || line == "\r") continue;
    if (line.back() == '\r') line.pop_back();
    const Rigid3 pose = PoseFromFields(
        SplitCsvLine(line), ConsecutiveColumns(0), path + ":" + std::to_string(line_number) + ": ");
    if (!(pose.translation.z() > 0.0)) {
      throw ConfigError(path + ":" + std::to_string(line_number) +
                        ": column 'tz': expected the marker in front of the camera (tz > 0)");
    }
    poses.push_back(pose);
  }
  if (poses.empty()) throw ConfigError(path + ": expected at least one pose row");
  return poses;
}

FrameRequest ExplicitFrames::Request(size_t i) const {
  FrameRequest request;
  request.scene.marker = &marker;
  request.scene.camera = camera;
  request.scene.cam_from_marker = poses.at(i);
  request.degradations = degradations;
  request.channels = channels;
  return request;
}

ExplicitFrames LoadExplicitFrames(const std::string& marker_path,
                                  const std::string& camera_path,
                                  const std::string& poses_path,
                                  const Degradations& degradations,
                                  Channels channels) {
  ExplicitFrames frames;
  frames.marker = LoadMarkerYaml(marker_path);
  frames.camera = LoadCameraYaml(camera_path);
  frames.poses = LoadPosesCsv(poses_path);
  frames.degradations = degradations;
  std::string error;
  if (!frames.degradations.IsValid(&error)) throw ConfigError("option: " + error);
  frames.channels = ChannelsFor(channels, frames.marker);
  return frames;
}

void RenderPoses(const ExplicitRenderOptions& o) {
  const ExplicitFrames frames = LoadExplicitFrames(
      o.marker_path, o.camera_path, o.poses_path, o.degradations, Channels::kAuto);
  CreateEmptyOutputFolder(o.out_dir, o.overwrite);
  const std::string& name = frames.marker.name;
  WriteDatasetFiles(
      o.out_dir,
      std::filesystem::path(o.poses_path).stem().string(),
      o.poses_path,
      o.camera_path,
      {{name, WriteScaledMarkerFile(o.marker_path, 1.0, o.out_dir + "/markers", name)}});
  GroundTruthCsv csv(o.out_dir);
  Progress progress("render " + frames.marker.name, frames.poses.size(), 0);
  for (size_t i = 0; i < frames.poses.size(); ++i) {
    FrameRequest request = frames.Request(i);
    request.keep_linear = o.write_float;
    request.noise_seed = SeedFor(o.seed, 0, i, SeedPurpose::kNoise);
    const RenderedFrame frame = RenderFrame(request);
    const std::string image = WriteFrame(o.out_dir, static_cast<int>(i), frame);
    csv.Write(static_cast<int>(i),
              image,
              frames.marker.name,
              {},
              o.seed,
              frames.camera,
              request,
              frame.truth,
              o.crlb ? BoundOf(PoseCrlb(request)) : FrameBound{});
    progress.Advance();
  }
  progress.Finish();
}

}  // namespace markerbench
