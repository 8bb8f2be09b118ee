// The report of a sequence scenario (a run whose manifest entry has a `trajectory`, issue 22):
// - DIR/<scenario>/sequences.csv: one row per sequence (cell, trial, marker) and tracker,
//   with bench/report/sequence_metrics.h's figures;
// - DIR/<scenario>/tum/<tracker>/<sequence>.tum and tum/truth/<sequence>.tum: each tracker's
//   camera trajectory and the ground truth, for `evo_ape tum truth.tum tracker.tum`;
// - rows of DIR/sequence_summary.csv and a report.md section: per cell, marker and tracker,
//   over the trials, with 95 % intervals (report.md's section is written by report.cc).
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "bench/metrics/intervals.h"
#include "bench/plan/trajectory_options.h"
#include "bench/report/sequence_metrics.h"
#include "bench/run/frames_csv.h"

namespace markerbench {

struct SequenceSummaryRow {
  std::string scenario;
  std::string sweep_parameter;
  double sweep_value = 0.0;
  std::string grid;
  std::string marker;
  std::string tracker;
  int sequences = 0;
  int visible = 0;  // frames where the marker shows, over the sequences
  int lost = 0;     // of those, frames without a pose
  int found_hidden = 0;
  Interval lost_rate_ci;  // Wilson, with the videos as the sample size (frames are clustered)
  // Medians over the sequences (metres, degrees, seconds, milliseconds); NaN when none.
  double ate_m = NAN;
  Interval ate_ci_m;
  double rpe_m = NAN;
  double rpe_deg = NAN;
  double jitter_m = NAN;
  // Over every occlusion of every sequence: the median re-acquisition time (+inf counts as
  // the longest), and how many were never followed by a pose.
  double reacquire_median_s = NAN;
  int occlusions = 0;
  int never_reacquired = 0;
  // The medians of the sequences' median times per frame (SequenceMetrics), with 95 %
  // intervals over the videos.
  double tracking_ms = NAN;
  Interval tracking_ci_ms;
  double detection_ms = NAN;
  Interval detection_ci_ms;
};

// The rows of one sequence: its identity and, per tracker in order of appearance, its frames.
struct SequenceRows {
  FrameRow first;  // scenario, sweep value, grid, trial, marker
  int last_frame = -1;
  int frames = 0;
  std::vector<Rigid3> truth;
  std::vector<std::string> trackers;
  std::map<std::string, std::vector<SequenceFrame>> of_tracker;
};

// One tracker's metrics over one sequence.
struct MeasuredSequence {
  FrameRow sequence;
  std::string tracker;
  SequenceMetrics metrics;
};

// Writes a scenario folder's sequences.csv and TUM files from its rows (frames.csv joined
// with timing.csv, in plan order), fed one at a time as the report streams them; `entry` is
// the scenario's manifest entry (its `trajectory`).
class SequenceResults {
 public:
  SequenceResults(const std::string& folder, const nlohmann::json& entry);
  // Whether the marker shows in the row's frame (false: an occlusion, which summary.csv
  // leaves to these metrics). Throws ConfigError for a row out of plan order (a sequence
  // longer than its trajectory).
  bool Add(const FrameRow& row, double time_ms);
  // Writes sequences.csv; the summary rows, in order of first appearance.
  std::vector<SequenceSummaryRow> Finish();

 private:
  // Writes the open sequence's TUM files and sequences.csv rows, and keeps its metrics.
  void Close();
  void WriteTum(const std::string& who, const std::string& name, const std::string& text) const;

  std::string folder_;
  TrajectoryOptions trajectory_;
  std::string csv_;
  std::optional<SequenceRows> open_;  // the sequence being read
  std::vector<MeasuredSequence> measured_;
};

// One summary row: `cell`'s identity (scenario to tracker) with its figures over `sequences`,
// the metrics of each of its videos.
SequenceSummaryRow SummaryOfSequences(const SequenceSummaryRow& cell,
                                      const std::vector<SequenceMetrics>& sequences);

std::string SequenceSummaryCsv(const std::vector<SequenceSummaryRow>& rows);

}  // namespace markerbench
