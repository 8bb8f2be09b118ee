#include "bench/run/dataset.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "bench/io/atomic_file.h"
#include "bench/run/frames_csv.h"
#include "bench/run/pose_columns.h"
#include "core/camera_yaml.h"
#include "core/config_error.h"
#include "core/file_bytes.h"
#include "core/marker_yaml.h"
#include "core/number_text.h"
#include "core/regular_file.h"

namespace markerbench {
namespace {

constexpr int kDatasetFormat = 1;

const char kReadme[] = R"(A markerbench dataset: %s, rendered from %s.

frame_NNNNNN.png   the frames (8-bit grey or RGB)
groundtruth.csv    one row per frame: the frame, its image, marker, sweep value and trial,
                   the camera (fx, fy, cx, cy, width, height), the true pose r11..r33, tx,
                   ty, tz, the degradations, apparent_size_px and the marker's keypoints
                   in pixels (keypoints_px: "u v" pairs separated by ";"); for a video
                   (a sequence scenario) its frame (from 0), the ground truth's time in
                   seconds (time_s, the middle row at mid-exposure), whether the marker is
                   hidden (occluded 1) and the exposure and rolling-shutter readout
                   (exposure_s, readout_s); sequence_frame and time_s are empty otherwise;
                   then the frame's Cramer-Rao bound on the camera centre's error (crlb_position_m
                   RMS, crlb_position_med_m median, m), the rotation's (crlb_rotation_deg,
                   crlb_rotation_med_deg) and the centre's covariance eigenvalues
                   (crlb_position_var1_m2..var3_m2): inf where the marker is hidden, empty
                   where not computed
camera.yaml        the camera (ROS camera_info; distortion plumb_bob, OpenCV's k1 k2 p1 p2 k3)
markers/NAME.yaml  each marker as the frames show it: multiply every length by its `scale`
dataset.json       the scenario's name and these files

Conventions:
- poses are cam_from_marker: x_cam = R x_marker + t, in metres, R row-major (r11 r12 r13
  is its first row); the camera centre in the marker frame is -R^T t;
- camera frame: x right, y down, z forward (OpenCV); marker frame: the marker's features at
  z = 0, x right, y up as printed, z out of the printed face (towards the camera); square
  markers' corners are (-s, +s), (+s, +s), (+s, -s), (-s, -s) with s half the black square;
- pixels: the top-left pixel's centre is (0, 0); pixel (u, v) covers [u-1/2, u+1/2] x
  [v-1/2, v+1/2];
- pixel values: 8 bits, linear in the light where the column gamma is 1; otherwise written
  by a camera response as 255 v^(1/gamma) for the linear value v in [0, 1] (noise added
  before it), which 255 (x/255)^gamma takes back.

Score a tracker's estimates with
  markerbench score DIR --poses ESTIMATES.csv --tracker NAME --out RUN_DIR
where ESTIMATES.csv has the header frame,status,r11,r12,r13,r21,r22,r23,r31,r32,r33,tx,ty,tz
(and optionally ,time_ms): status ok, not_detected, wrong_id, pose_failed or error; more
hypotheses of a frame as further rows of it, best first. RUN_DIR works with markerbench
report and check like a sweep's.
)";

std::string Located(const std::string& path, int line) {
  return path + ":" + std::to_string(line) + ": ";
}

}  // namespace

void WriteDatasetFiles(const std::string& dir,
                       const std::string& scenario_name,
                       const std::string& source,
                       const std::string& camera_path,
                       const std::map<std::string, std::string>& marker_files) {
  WriteFileAtomically(dir + "/camera.yaml", ReadFileBytes(camera_path));
  nlohmann::json dataset = {{"format", kDatasetFormat},
                            {"scenario", scenario_name},
                            {"source", source},
                            {"camera", "camera.yaml"},
                            {"groundtruth", "groundtruth.csv"}};
  for (const auto& [name, path] : marker_files) {
    dataset["markers"][name] = std::filesystem::relative(path, dir).string();
  }
  WriteFileAtomically(dir + "/dataset.json", dataset.dump(2) + "\n");
  std::vector<char> readme(sizeof(kReadme) + scenario_name.size() + source.size());
  std::snprintf(readme.data(), readme.size(), kReadme, scenario_name.c_str(), source.c_str());
  WriteFileAtomically(dir + "/README.txt", readme.data());
}

Dataset ReadDataset(const std::string& dir) {
  const std::string json_path = dir + "/dataset.json";
  RequireRegularFile(json_path);
  const nlohmann::json json = nlohmann::json::parse(ReadFileBytes(json_path), nullptr, false);
  if (!json.is_object() || json.value("format", 0) != kDatasetFormat ||
      !json.value("scenario", nlohmann::json()).is_string() ||
      !json.value("markers", nlohmann::json()).is_object()) {
    throw ConfigError(json_path + ": expected a markerbench dataset (format " +
                      std::to_string(kDatasetFormat) + ") with scenario and markers");
  }
  Dataset dataset;
  dataset.scenario = json["scenario"].get<std::string>();
  dataset.camera = LoadCameraYaml(dir + "/" + json.value("camera", "camera.yaml"));
  for (const auto& [name, file] : json["markers"].items()) {
    if (!file.is_string()) throw ConfigError(json_path + ": markers." + name + ": expected a path");
    MarkerSpec marker = LoadMarkerYaml(dir + "/" + file.get<std::string>());
    marker.name = name;
    dataset.markers[name] = marker;
  }

  const std::string csv_path = dir + "/groundtruth.csv";
  RequireRegularFile(csv_path);
  std::ifstream in(csv_path);
  std::string line;
  // A line read without the CR of a CRLF file (one edited on Windows).
  const auto next_line = [&] {
    const bool read = static_cast<bool>(std::getline(in, line));
    if (read && !line.empty() && line.back() == '\r') line.pop_back();
    return read;
  };
  next_line();
  const std::vector<std::string> header = SplitCsvLine(line);
  auto column = [&](const std::string& name) {
    const auto at = std::find(header.begin(), header.end(), name);
    if (at == header.end()) throw ConfigError(csv_path + ":1: no column '" + name + "'");
    return static_cast<size_t>(at - header.begin());
  };
  const size_t frame = column("frame"), marker = column("marker"),
               parameter = column("sweep_parameter"), value = column("sweep_value"),
               trial = column("trial"), seed = column("seed"), size = column("apparent_size_px");
  std::array<size_t, 12> pose;
  for (size_t k = 0; k < 12; ++k) pose[k] = column(kPoseColumns[k]);
  // A grid sweep's other axes; datasets written before grids have no such column.
  const auto grid_at = std::find(header.begin(), header.end(), "grid");
  // The frame's Cramér-Rao bound; datasets written before it have none of its columns.
  std::vector<size_t> bound_at;
  if (std::find(header.begin(), header.end(), FrameBoundColumns()[0]) != header.end()) {
    for (const std::string& name : FrameBoundColumns()) bound_at.push_back(column(name));
  }
  for (int number = 2; next_line(); ++number) {
    const std::vector<std::string> f = SplitCsvLine(line);
    if (f.size() != header.size()) {
      throw ConfigError(Located(csv_path, number) + "expected " + std::to_string(header.size()) +
                        " fields, got " + std::to_string(f.size()));
    }
    auto number_at = [&](size_t i) {
      const std::optional<double> v = ParseFiniteNumber(f[i]);
      if (!v) {
        throw ConfigError(Located(csv_path, number) + "column '" + header[i] +
                          "': expected a number, got '" + f[i] + "'");
      }
      return *v;
    };
    // Counts and the seed read exactly, never through an out-of-range cast.
    auto count_at = [&](size_t i) {
      const std::optional<long long> v =
          ParseWholeNumber(f[i], 0.0, std::numeric_limits<int>::max());
      if (!v) {
        throw ConfigError(Located(csv_path, number) + "column '" + header[i] +
                          "': expected a whole number >= 0, got '" + f[i] + "'");
      }
      return static_cast<int>(*v);
    };
    DatasetFrame d;
    d.frame = count_at(frame);
    d.marker = f[marker];
    if (!dataset.markers.count(d.marker)) {
      throw ConfigError(Located(csv_path, number) + "marker '" + d.marker +
                        "' is not in dataset.json");
    }
    d.sweep_parameter = f[parameter].empty() ? "pose" : f[parameter];
    d.sweep_value = f[parameter].empty() ? d.frame : number_at(value);
    d.trial = f[parameter].empty() ? 0 : count_at(trial);
    if (grid_at != header.end()) d.grid = f[static_cast<size_t>(grid_at - header.begin())];
    const std::optional<uint64_t> seed_value = ParseUnsigned64(f[seed]);
    if (!seed_value) {
      throw ConfigError(Located(csv_path, number) +
                        "column 'seed': expected a whole number, got '" + f[seed] + "'");
    }
    d.seed = *seed_value;
    d.truth = PoseFromFields(f, pose, Located(csv_path, number));
    d.apparent_size_px = number_at(size);
    if (!bound_at.empty()) {
      // Empty: not computed; "inf": nothing to see; else a number >= 0.
      std::array<double, kFrameBoundColumns> values;
      for (size_t k = 0; k < bound_at.size(); ++k) {
        const std::string& text = f[bound_at[k]];
        values[k] = text.empty() ? NAN : text == "inf" ? INFINITY : number_at(bound_at[k]);
        if (values[k] < 0.0) {
          throw ConfigError(Located(csv_path, number) + "column '" + header[bound_at[k]] +
                            "': expected a bound >= 0, empty or inf, got '" + text + "'");
        }
      }
      d.bound = BoundFromValues(values);
    }
    dataset.frames.push_back(d);
  }
  if (dataset.frames.empty()) throw ConfigError(csv_path + ": no frames");
  return dataset;
}

}  // namespace markerbench
