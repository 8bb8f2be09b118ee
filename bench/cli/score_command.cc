#include "bench/cli/score_command.h"

#include <filesystem>
#include <fstream>
#include <limits>
#include <map>

#include "bench/io/atomic_file.h"
#include "bench/io/output_folder.h"
#include "bench/run/dataset.h"
#include "bench/run/frame_bound.h"
#include "bench/run/frames_csv.h"
#include "bench/run/manifest.h"
#include "bench/run/pose_columns.h"
#include "core/config_error.h"
#include "core/number_text.h"
#include "core/regular_file.h"
#include "core/sha256.h"

namespace markerbench {
namespace {

struct Estimate {
  TrackStatus status = TrackStatus::kNotDetected;
  std::vector<Rigid3> hypotheses;
  std::optional<double> time_ms;
  int line = 0;  // its first row
};

std::map<int, Estimate> ReadEstimates(const std::string& path, const Dataset& dataset) {
  RequireRegularFile(path);
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  std::string header = "frame,status";
  for (const char* c : kPoseColumns) header += std::string(",") + c;
  const bool timed = line == header + ",time_ms";
  if (line != header && !timed) {
    throw ConfigError(path + ":1: expected the header '" + header +
                      "' (and optionally ',time_ms')");
  }
  std::map<int, bool> known;
  for (const DatasetFrame& f : dataset.frames) known[f.frame] = true;
  std::map<int, Estimate> estimates;
  for (int number = 2; std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    const std::string at = path + ":" + std::to_string(number) + ": ";
    const std::vector<std::string> f = SplitCsvLine(line);
    if (f.size() != (timed ? 15u : 14u)) {
      throw ConfigError(at + "expected " + std::to_string(timed ? 15 : 14) + " fields, got " +
                        std::to_string(f.size()));
    }
    const std::optional<long long> frame_number =
        ParseWholeNumber(f[0], 0.0, std::numeric_limits<int>::max());
    if (!frame_number || !known.count(static_cast<int>(*frame_number))) {
      throw ConfigError(at + "column 'frame': '" + f[0] + "' is not a frame of the dataset");
    }
    const int frame = static_cast<int>(*frame_number);
    const std::optional<TrackStatus> status = TrackStatusFromString(f[1]);
    if (!status) {
      throw ConfigError(at +
                        "column 'status': expected ok, not_detected, wrong_id, pose_failed "
                        "or error, got '" +
                        f[1] + "'");
    }
    const bool first = !estimates.count(frame);
    Estimate& e = estimates[frame];
    if (first) {
      e.status = *status;
      e.line = number;
    } else if (e.status != *status) {
      throw ConfigError(at + "frame " + std::to_string(frame) + " is '" + f[1] + "' here but '" +
                        ToString(e.status) + "' on line " + std::to_string(e.line));
    }
    if (timed && first && !f[14].empty()) {
      e.time_ms = ParseFiniteNumber(f[14]);
      if (!e.time_ms || *e.time_ms < 0.0) {
        throw ConfigError(at + "column 'time_ms': expected a time, got '" + f[14] + "'");
      }
    }
    if (*status != TrackStatus::kOk) continue;
    e.hypotheses.push_back(PoseFromFields(f, ConsecutiveColumns(2), at));
  }
  return estimates;
}

}  // namespace

void RunScoreCommand(const ScoreOptions& o, std::ostream& out) {
  const Dataset dataset = ReadDataset(o.dataset_dir);
  const std::map<int, Estimate> estimates = ReadEstimates(o.estimates_path, dataset);
  const std::string dir = o.out_dir + "/" + dataset.scenario;
  if (std::filesystem::exists(dir + "/frames.csv")) {
    throw ConfigError(dir + ": already holds a run; choose another --out");
  }
  CreateOutputFolder(dir);
  std::string frames = FramesCsvHeader(), timing = TimingCsvHeader();
  bool every_time = true;
  int missing = 0;
  for (const DatasetFrame& d : dataset.frames) {
    FrameRow row;
    row.scenario = dataset.scenario;
    row.sweep_parameter = d.sweep_parameter;
    row.sweep_value = d.sweep_value;
    row.grid = d.grid;
    row.trial = d.trial;
    row.frame = d.frame;
    row.marker = d.marker;
    row.tracker = o.tracker;
    row.seed = d.seed;
    row.apparent_size_px = d.apparent_size_px;
    row.distance_m = DistanceToMarker(d.truth, dataset.markers.at(d.marker));
    row.truth = d.truth;
    row.bound = d.bound;
    const auto e = estimates.find(d.frame);
    if (e == estimates.end()) {
      ++missing;
      row.message = "no estimate";
    } else {
      SetTrackResult(e->second.status, e->second.hypotheses, &row);
    }
    frames += FormatFrameRow(row);
    if (e != estimates.end() && e->second.time_ms) {
      timing += FormatTimingRow(row, *e->second.time_ms, *e->second.time_ms);
    } else {
      every_time = false;
    }
  }
  WriteFileAtomically(dir + "/frames.csv", frames);
  if (every_time) WriteFileAtomically(dir + "/timing.csv", timing);
  nlohmann::json entry;
  entry["dataset"] = o.dataset_dir;
  entry["estimates"] = {{"path", o.estimates_path}, {"sha256", Sha256OfFile(o.estimates_path)}};
  entry["tracker"] = o.tracker;
  entry["frames"] = dataset.frames.size();
  entry["frames_without_estimate"] = missing;
  UpdateManifest(o.out_dir + "/manifest.json", dataset.scenario, EnvironmentManifest(1), entry);
  out << dataset.scenario << ": scored " << dataset.frames.size() << " frames of " << o.tracker
      << " into " << dir << "; " << missing << " had no estimate (not_detected)\n";
}

}  // namespace markerbench
