// frames.csv (architecture.md, "Per-frame results"): one tidy row per frame × tracker. Every
// column is a function of the scenario and seed, so the file is byte-identical across runs
// and thread counts; the measured call times go to timing.csv.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "bench/metrics/metrics.h"
#include "core/rigid3.h"
#include "trackers/tracker.h"

namespace markerbench {

// A frame's Cramér-Rao bound (renderer/pose_crlb.h): the RMS and median camera-centre error
// and the RMS and median rotation error of an efficient estimator, and the eigenvalues of its
// camera-centre covariance, ascending (the chance of success of such an estimator:
// ProbabilityNormWithin). NaN (an empty field): not computed (a scenario's crlb: false, or
// render --no-crlb).
// Infinite: nothing to see (the marker hidden, or a pose direction the image does not show).
struct FrameBound {
  double position_m = NAN;      // RMS of the camera centre's error
  double position_med_m = NAN;  // its median
  double rotation_deg = NAN;
  double rotation_med_deg = NAN;
  Eigen::Vector3d position_variances_m2 = Eigen::Vector3d::Constant(NAN);
};

struct FrameRow {
  std::string scenario;
  std::string sweep_parameter;
  double sweep_value = 0.0;
  std::string grid;  // a grid sweep's other axes at this cell (bench/plan/frame_plan.h); else empty
  int trial = 0;
  int frame = 0;  // index in the scenario's frame plan
  std::string marker;
  std::string tracker;
  uint64_t seed = 0;  // the scenario seed
  double apparent_size_px = 0.0;
  double distance_m = 0.0;  // true distance from the camera centre to the marker centre
  TrackStatus status = TrackStatus::kNotDetected;
  int hypotheses = 0;
  PoseErrors errors{};
  FrameBound bound;  // the same for every tracker
  Rigid3 truth;
  std::optional<Rigid3> estimate;  // the first hypothesis, when the status is ok
  std::string message;
};

// Sets the row's result from a tracker's status and hypotheses (best first), against the
// row's truth: the errors and the estimate only with status ok and a hypothesis.
void SetTrackResult(TrackStatus status, const std::vector<Rigid3>& hypotheses, FrameRow* row);

// The header line and one row, each ending in '\n'.
std::string FramesCsvHeader();
std::string FormatFrameRow(const FrameRow& row);

// Parses one data line (without its '\n'); throws std::runtime_error naming the column.
FrameRow ParseFrameRow(const std::string& line);

// timing.csv: one row per frames.csv row, in the same order: frame, scenario, tracker,
// success (1 when the row's pose is within kSuccessFraction of the distance, else 0), time_ms,
// round_trip_ms.
std::string TimingCsvHeader();
inline constexpr size_t kTimingFrameColumn = 0;
inline constexpr size_t kTimingTrackerColumn = 2;
inline constexpr size_t kTimingTimeColumn = 4;
inline constexpr size_t kTimingColumnCount = 6;
// time_ms: the tracker's own time when it reports one (an isolated worker, an external
// tracker's time_ms), else the round trip; round_trip_ms: Track() as the runner timed it,
// process I/O included.
std::string FormatTimingRow(const FrameRow& row, double time_ms, double round_trip_ms);

// One field, in RFC 4180 quotes when it holds a comma or a quote; line breaks become spaces
// (one row per line).
std::string CsvField(std::string text);

// Fields of one CSV line, with RFC 4180 quotes.
std::vector<std::string> SplitCsvLine(const std::string& line);

}  // namespace markerbench
