// A rendered dataset: `markerbench render`'s output folder, self-contained for programs
// outside markerbench and for `score`. It holds frame_NNNNNN.png, groundtruth.csv,
// camera.yaml (a copy of the camera file), markers/<name>.yaml (each marker as the frames
// show it, with its equal-area `scale`), dataset.json (the scenario's name and those files)
// and README.txt (the conventions).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "bench/run/frame_bound.h"
#include "core/camera.h"
#include "core/marker_spec.h"
#include "core/rigid3.h"

namespace markerbench {

// Writes camera.yaml, dataset.json and README.txt into `dir`; `marker_files` are the marker
// files already written into dir/markers, by name. `source` says what was rendered.
void WriteDatasetFiles(const std::string& dir,
                       const std::string& scenario_name,
                       const std::string& source,
                       const std::string& camera_path,
                       const std::map<std::string, std::string>& marker_files);

struct DatasetFrame {
  int frame = 0;
  std::string marker;
  // The explicit render form has no sweep: each pose is its own cell ("pose", its index).
  std::string sweep_parameter;
  double sweep_value = 0.0;
  std::string grid;  // a grid sweep's other axes (frames.csv's grid); else empty
  int trial = 0;
  uint64_t seed = 0;
  Rigid3 truth;  // cam_from_marker
  double apparent_size_px = 0.0;
  FrameBound bound;  // NaN in a dataset written before groundtruth.csv gave it
};

struct Dataset {
  std::string scenario;
  Camera camera;
  std::map<std::string, MarkerSpec> markers;  // by name
  std::vector<DatasetFrame> frames;           // in groundtruth.csv's order
};

// Throws ConfigError naming the file (and line) of anything missing or malformed.
Dataset ReadDataset(const std::string& dir);

}  // namespace markerbench
